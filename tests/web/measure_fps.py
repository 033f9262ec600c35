#!/usr/bin/python3
"""Frames per second of the web page (docs/web.md) in headless Chromium, per n_seg: the
figure behind the page's n_seg slider maximum (kWebMaxSegments in app/web/web_main.cpp).
A measurement, not a test.

Usage: tests/web/measure_fps.py [--page-dir build/web] [--frames 300] N_SEG...
For each n_seg: opens the page at 1280x720 with ?n_seg=N (the compress scene, playing),
and times `--frames` frames from the first one drawn, as the desktop's
`invfree live --frames 300 --bench` does. Prints one line per n_seg: frames/s (wall
clock), and the CPU time all of the browser's processes spent per frame (the page's
thread, SwiftShader's, the compositor's; from /proc). On a loaded machine the first falls
with the share of the cores the browser gets; the second does not (much): a frame whose
CPU time is under 33.3 ms holds 30 frames/s on an idle machine even if all its work ran
one after the other on one core.

--select: before timing, a click at the centroid of the triangle nearest the body's middle
(Module._invfree_triangle_window_x/y) inspects it, so the frames include the inspector's
analysis, its window and the outline (issue 26's picking); the line then names the
triangle.

--scene NAME: that built-in scene instead of compress (issue 27's shapes: ring, c-shape,
plate-hole, bunny). For a scene with a meshed shape the line also gives the page's
meshing time at that n_seg: CGAL's mesher in WebAssembly (Module._invfree_mesh_ms, the
median of 5 meshings of the scene's shapes, uncached) and the triangles it made.
"""

import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import page_driver as pd  # noqa: E402


def browser_cpu_seconds(root_pid):
    """User + system CPU time of `root_pid` (chromedriver) and all its descendants: the
    browser's processes (page, GPU/SwiftShader, network, ...)."""
    children, times = {}, {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        pid, ppid = int(entry), int(fields[1])
        children.setdefault(ppid, []).append(pid)
        times[pid] = int(fields[11]) + int(fields[12])  # utime + stime, clock ticks
    total, todo = 0, [root_pid]
    while todo:
        pid = todo.pop()
        total += times.get(pid, 0)
        todo.extend(children.get(pid, []))
    return total / os.sysconf("SC_CLK_TCK")


def select_middle_triangle(driver, state):
    """Clicks the centroid of the triangle nearest the middle of the body's triangles right
    of the panel; returns the index of the triangle the page reports selected."""
    from selenium.webdriver.common.action_chains import ActionChains
    centroids = driver.execute_script(
        "const out = []; for (let t = 0; t < arguments[0]; ++t)"
        "  out.push([Module._invfree_triangle_window_x(t), Module._invfree_triangle_window_y(t)]);"
        "return out;", state["triangles"])
    panel_right = max(r[2] for name, r in state["widgets"].items() if name not in ("note", "inspector", "picture"))
    visible = [t for t, (x, y) in enumerate(centroids) if x is not None and x > panel_right + 12]
    if not visible:
        raise SystemExit(f"no triangle right of the panel (x {panel_right}) to select: {centroids[:4]}... "
                         f"widgets {state['widgets']}")
    mx = sum(centroids[t][0] for t in visible) / len(visible)
    my = sum(centroids[t][1] for t in visible) / len(visible)
    t = min(visible, key=lambda t: (centroids[t][0] - mx) ** 2 + (centroids[t][1] - my) ** 2)
    actions = ActionChains(driver)
    actions.w3c_actions.pointer_action.move_to_location(int(centroids[t][0]), int(centroids[t][1]))
    actions.w3c_actions.pointer_action.click()
    actions.perform()
    # The page is playing: the body may have moved a little under the pointer since the
    # centroids were read, so whichever triangle the click found is the one timed.
    state = pd.wait_for(driver, lambda s: s.get("selected") is not None,
                        f"a triangle to be selected by a click at triangle {t}'s centroid")
    return state["selected"]["triangle"]


def measure(driver, url, n_seg, frames, select=False, scene=""):
    driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                           {"width": 1280, "height": 720, "deviceScaleFactor": 1, "mobile": False})
    driver.get(f"{url}?n_seg={n_seg}" + (f"&scene={scene}" if scene else ""))
    first = pd.wait_for(driver, lambda s: s["frames"] >= 1, "the first frame",
                        stop_on_console_error=True)
    if first["n_seg"] != n_seg:
        raise SystemExit(f"n_seg={n_seg} was not applied (page note: {first['note']})")
    if scene and first["scene"] != scene:
        raise SystemExit(f"scene={scene} was not picked (the page shows {first['scene']})")
    mesh = None
    if scene:
        ms = driver.execute_script("return Module._invfree_mesh_ms(5);")
        if ms >= 0:
            mesh = (ms, int(driver.execute_script("return Module._invfree_mesh_triangles();")))
        first = pd.page_state(driver)
    selected = None
    if select:
        if "selected" not in first:
            raise SystemExit("--select: this page has no picking (no window.invfree.selected)")
        selected = select_middle_triangle(driver, first)
        first = pd.page_state(driver)
    driver_pid = driver.service.process.pid
    start, cpu_start = time.monotonic(), browser_cpu_seconds(driver_pid)
    last = pd.wait_for(driver, lambda s: s["frames"] >= first["frames"] + frames,
                       f"{frames} frames", timeout=600)
    seconds, cpu = time.monotonic() - start, browser_cpu_seconds(driver_pid) - cpu_start
    drawn = last["frames"] - first["frames"]
    if select and (last.get("selected") or {}).get("triangle") != selected:
        raise SystemExit(f"triangle {selected} was released while timing: {last.get('selected')}")
    return drawn / seconds, 1e3 * cpu / drawn, last["step_ms"], last["steps"], selected, mesh


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--page-dir", default=os.path.join(os.path.dirname(__file__), "../../build/web"))
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("--select", action="store_true",
                        help="inspect the middle triangle (a click at its centroid) before timing")
    parser.add_argument("--scene", default="", help="a built-in scene (default: compress)")
    parser.add_argument("n_seg", type=int, nargs="+")
    args = parser.parse_args()
    missing = pd.missing_toolchain(args.page_dir)
    if missing:
        raise SystemExit(f"measure_fps: {missing}")
    server = pd.PageServer(args.page_dir)
    driver = pd.open_browser()
    try:
        for n in args.n_seg:
            fps, cpu_ms, step_ms, steps, selected, mesh = measure(
                driver, server.url, n, args.frames, args.select, args.scene)
            what = f", triangle {selected} inspected" if selected is not None else ""
            if args.scene:
                what = f" ({args.scene}" + (f", meshed in {mesh[0]:.1f} ms, {mesh[1]} triangles" if mesh else "") + ")" + what
            print(f"web fps: n_seg {n}{what}: {fps:.1f} frames/s, browser CPU {cpu_ms:.1f} ms/frame "
                  f"over {args.frames} frames ({steps} steps, {step_ms:.2f} ms/step), "
                  f"load average {os.getloadavg()[0]:.1f}", flush=True)
    finally:
        driver.quit()
        server.close()


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Frames per second of the web page (docs/web.md) in headless Chromium, per n_seg: the
figure behind the page's n_seg slider maximum (kWebMaxSegments in app/web/web_main.cpp).
A measurement, not a test.

Usage: tests/web/measure_fps.py [--page-dir build/web] [--frames 300] N_SEG...
For each n_seg: opens the page at 1280x720 with ?n_seg=N (the compress scene, playing),
and times `--frames` frames from the first one drawn, as the desktop's
`invfree live --frames 300 --bench` does. Prints one line per n_seg.
"""

import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import page_driver as pd  # noqa: E402


def measure(driver, url, n_seg, frames):
    driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                           {"width": 1280, "height": 720, "deviceScaleFactor": 1, "mobile": False})
    driver.get(f"{url}?n_seg={n_seg}")
    first = pd.wait_for(driver, lambda s: s["frames"] >= 1, "the first frame")
    if first["n_seg"] != n_seg:
        raise SystemExit(f"n_seg={n_seg} was not applied (page note: {first['note']})")
    start = time.monotonic()
    last = pd.wait_for(driver, lambda s: s["frames"] >= first["frames"] + frames,
                       f"{frames} frames", timeout=600)
    seconds = time.monotonic() - start
    drawn = last["frames"] - first["frames"]
    return drawn / seconds, last["step_ms"], last["steps"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--page-dir", default=os.path.join(os.path.dirname(__file__), "../../build/web"))
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("n_seg", type=int, nargs="+")
    args = parser.parse_args()
    missing = pd.missing_toolchain(args.page_dir)
    if missing:
        raise SystemExit(f"measure_fps: {missing}")
    server = pd.PageServer(args.page_dir)
    driver = pd.open_browser()
    try:
        for n in args.n_seg:
            fps, step_ms, steps = measure(driver, server.url, n, args.frames)
            print(f"web fps: n_seg {n}: {fps:.1f} frames/s over {args.frames} frames "
                  f"({steps} steps, {step_ms:.2f} ms/step), load average {os.getloadavg()[0]:.1f}",
                  flush=True)
    finally:
        driver.quit()
        server.close()


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The web page (docs/web.md) in headless Chromium: it loads with no console error, the
simulation advances (step count and min det F read from window.invfree), the mu slider
changes mu and the picture, the first frame matches its golden, the Screenshot button
downloads a PNG of what the page shows, and a touch tap plays and pauses.

Usage: web_page_test.py PAGE_DIR GOLDEN_DIR OUT_DIR
  PAGE_DIR    the built page (build/web: index.html, index.js, index.wasm)
  GOLDEN_DIR  tests/web/goldens; INVFREE_UPDATE_GOLDENS=1 writes the golden instead
  OUT_DIR     where a failing comparison leaves the actual and difference images
Exit: 0 all passed, 1 a check failed, 77 skipped (the toolchain or the page is missing;
the reason is printed).

Golden rule: the desktop's (tests/render/image_compare.h): at most 0.1% of the pixels may
differ by more than 5/255 in a channel. The golden is this browser's own picture: WebGL 2
in headless Chromium is rasterized by SwiftShader, not by the desktop's llvmpipe, so the
desktop goldens are not compared here.
"""

import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import page_driver as pd  # noqa: E402

WIDTH, HEIGHT = 1280, 720
STEPS = 50  # clicks on Step: the square has landed on the ground after ~32 steps


def fail(message):
    raise AssertionError(message)


def load(driver, url):
    driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                           {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1,
                            "mobile": False})
    driver.get_log("browser")  # drop what an earlier page left
    driver.get(url)
    return pd.wait_for(driver, lambda s: s["frames"] >= 3, "the page's first frames",
                       stop_on_console_error=True)


def screenshot(driver):
    import io
    from PIL import Image
    return Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("RGB")


def differing_pixels(a, b, threshold=5):
    """Pixels whose largest channel difference exceeds `threshold` (images of one size)."""
    from PIL import ImageChops
    diff = ImageChops.difference(a, b)
    channels = diff.split()
    biggest = ImageChops.lighter(ImageChops.lighter(channels[0], channels[1]), channels[2])
    over = biggest.point(lambda v: 255 if v > threshold else 0)
    return sum(1 for v in over.getdata() if v), biggest


def click(driver, x, y):
    from selenium.webdriver.common.action_chains import ActionChains
    actions = ActionChains(driver)
    actions.w3c_actions.pointer_action.move_to_location(int(x), int(y))
    actions.w3c_actions.pointer_action.click()
    actions.perform()


def centre(rect, fraction_x=0.5):
    x0, y0, x1, y1 = rect
    return x0 + fraction_x * (x1 - x0), 0.5 * (y0 + y1)


def step_n_times(driver, n):
    """Clicks the panel's Step button n times, each once the previous step is done."""
    state = pd.page_state(driver)
    for _ in range(n):
        before = state["steps"]
        click(driver, *centre(state["widgets"]["step"]))
        state = pd.wait_for(driver, lambda s, b=before: s["steps"] == b + 1,
                            f"step {before + 1} after a click on Step")
    return state


def check_no_console_error(driver, what):
    errors = pd.console_errors(driver)
    if errors:
        fail(f"{what}: console errors: {errors}")


def test_first_frame(driver, url, golden_dir, out_dir):
    load(driver, url + "?paused=1")
    check_no_console_error(driver, "paused page")
    actual = screenshot(driver)
    golden = os.path.join(golden_dir, "first_frame.png")
    if os.environ.get("INVFREE_UPDATE_GOLDENS") == "1":
        actual.save(golden)
        print(f"wrote {golden}")
        return
    from PIL import Image
    if not os.path.isfile(golden):
        fail(f"no golden {golden} (INVFREE_UPDATE_GOLDENS=1 writes it)")
    expected = Image.open(golden).convert("RGB")
    if expected.size != actual.size:
        fail(f"first frame is {actual.size}, golden {expected.size}")
    differing, biggest = differing_pixels(actual, expected)
    allowed = int(0.001 * WIDTH * HEIGHT)
    if differing > allowed:
        os.makedirs(out_dir, exist_ok=True)
        actual.save(os.path.join(out_dir, "first_frame_actual.png"))
        biggest.point(lambda v: min(255, 16 * v)).save(os.path.join(out_dir, "first_frame_diff.png"))
        fail(f"first frame differs from {golden} in {differing} pixels (> {allowed}); "
             f"actual and 16x difference in {out_dir}")
    print(f"first frame matches its golden ({differing} of {WIDTH * HEIGHT} pixels over 5/255)")


def test_advances(driver, url):
    first = load(driver, url)
    if not first["playing"]:
        fail("the page did not start playing")
    later = pd.wait_for(driver, lambda s: s["steps"] >= first["steps"] + 60 and s["min_det_f"] < 0.99,
                        "60 more steps and a deformed square (min det F < 0.99)", timeout=300)
    check_no_console_error(driver, "playing page")
    print(f"advances: steps {first['steps']} -> {later['steps']}, "
          f"min det F {first['min_det_f']:.4f} -> {later['min_det_f']:.4f}")


def test_mu_slider(driver, url):
    # The same 50 steps from the same start, once with the scene's mu and once with a mu
    # picked on the slider near its soft end: mu, min det F and the picture must differ.
    load(driver, url + "?paused=1")
    reference = step_n_times(driver, STEPS)
    reference_picture = screenshot(driver)

    start = load(driver, url + "?paused=1")
    click(driver, *centre(start["widgets"]["mu"], 0.1))
    changed = pd.wait_for(driver, lambda s: s["mu"] != start["mu"], "mu to follow the slider")
    if not changed["mu"] < start["mu"]:
        fail(f"a click near the slider's left end raised mu: {start['mu']} -> {changed['mu']}")
    if changed["lambda"] != start["lambda"]:
        fail(f"the mu slider changed lambda: {start['lambda']} -> {changed['lambda']}")
    softer = step_n_times(driver, STEPS)
    softer_picture = screenshot(driver)
    check_no_console_error(driver, "mu slider")

    if softer["min_det_f"] == reference["min_det_f"]:
        fail(f"min det F after {STEPS} steps is the same with mu {start['mu']} and {softer['mu']}")
    # The picture right of the panel (the body, planes, colour bar, statistics).
    panel_right = int(start["widgets"]["n_seg"][2]) + 80
    box = (panel_right, 0, WIDTH, HEIGHT)
    differing, _ = differing_pixels(reference_picture.crop(box), softer_picture.crop(box))
    if differing < 500:
        fail(f"the picture barely changed with mu ({differing} pixels differ)")
    print(f"mu slider: mu {start['mu']:.1f} -> {softer['mu']:.1f} Pa; after {STEPS} steps min det F "
          f"{reference['min_det_f']:.4f} -> {softer['min_det_f']:.4f}, {differing} pixels differ")


def test_screenshot_download(driver, url, out_dir):
    # The Screenshot button sits between Reset and Record on the panel's first row.
    import tempfile
    from PIL import Image
    state = load(driver, url + "?paused=1")
    downloads = tempfile.mkdtemp(prefix="invfree_web_downloads_")
    driver.execute_cdp_cmd("Page.setDownloadBehavior", {"behavior": "allow", "downloadPath": downloads})
    reset, record = state["widgets"]["reset"], state["widgets"]["record"]
    click(driver, 0.5 * (reset[2] + record[0]), 0.5 * (reset[1] + reset[3]))
    path = os.path.join(downloads, "invfree_0001.png")
    deadline = time.monotonic() + 60
    while not os.path.isfile(path) and time.monotonic() < deadline:
        time.sleep(0.1)
    if not os.path.isfile(path):
        fail(f"no download {path} after a click on Screenshot (found: {os.listdir(downloads)})")
    time.sleep(0.5)  # the browser renames the finished download into place: let it settle
    downloaded = Image.open(path).convert("RGB")
    shown = screenshot(driver)
    if downloaded.size != shown.size:
        fail(f"the downloaded PNG is {downloaded.size}, the page {shown.size}")
    # The right half (the body, the planes, the colour bar, the statistics): on the panel
    # the button's hover and tooltip change between the click and the page's screenshot.
    box = (WIDTH // 2, 0, WIDTH, HEIGHT)
    differing, _ = differing_pixels(downloaded.crop(box), shown.crop(box))
    if differing > int(0.001 * (WIDTH // 2) * HEIGHT):
        os.makedirs(out_dir, exist_ok=True)
        downloaded.save(os.path.join(out_dir, "screenshot_download.png"))
        fail(f"the downloaded PNG differs from the page in {differing} pixels")
    check_no_console_error(driver, "screenshot")
    print(f"screenshot: downloaded {os.path.basename(path)}, {downloaded.size[0]}x{downloaded.size[1]}, "
          f"{differing} pixels of its right half differ from the page's")


def touch_tap(driver, x, y):
    # A 50 ms tap by the events' own time stamps, however long a loaded page takes to
    # handle the first before the protocol sends the second (the page times a tap by them).
    point = [{"x": int(x), "y": int(y)}]
    start = time.time()
    driver.execute_cdp_cmd("Input.dispatchTouchEvent",
                           {"type": "touchStart", "touchPoints": point, "timestamp": start})
    driver.execute_cdp_cmd("Input.dispatchTouchEvent",
                           {"type": "touchEnd", "touchPoints": [], "timestamp": start + 0.05})


def test_touch_tap(driver, url):
    # A tap on the picture (below the body, between the planes' hatching and the colour
    # bar) plays the paused page and a second one pauses it; a tap on the panel where it
    # is empty (right of the mu slider, which has no label; the panel's last rows may reach
    # the bottom of a 720 px page, so not below them) does neither.
    state = load(driver, url + "?paused=1")
    mu, colours = state["widgets"]["mu"], state["widgets"]["colours"]  # colours: the panel's right edge
    panel_x, panel_y = 0.5 * (mu[2] + colours[2]), 0.5 * (mu[1] + mu[3])
    if colours[2] - mu[2] < 40:
        fail(f"no empty panel right of the mu slider to tap in (slider ends at x {mu[2]:.0f}, "
             f"the panel's widgets at {colours[2]:.0f})")
    touch_tap(driver, panel_x, panel_y)
    frames = pd.page_state(driver)["frames"]
    after_panel = pd.wait_for(driver, lambda s: s["frames"] >= frames + 5, "frames after a tap on the panel")
    if after_panel["playing"]:
        fail("a tap on the panel started playing")
    touch_tap(driver, 700, HEIGHT - 60)
    pd.wait_for(driver, lambda s: s["playing"], "a tap on the picture to play")
    touch_tap(driver, 700, HEIGHT - 60)
    pd.wait_for(driver, lambda s: not s["playing"], "a second tap to pause")
    check_no_console_error(driver, "touch")
    print("touch: a tap on the picture plays and pauses, a tap on the panel does not")


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    page_dir, golden_dir, out_dir = sys.argv[1:]
    missing = pd.missing_toolchain(page_dir)
    if missing:
        print(f"SKIPPED: web page tests: {missing}")
        return pd.SKIP
    age_min = (time.time() - os.path.getmtime(os.path.join(page_dir, "index.wasm"))) / 60
    print(f"page: {page_dir} (index.wasm built {age_min:.0f} min ago)")
    server = pd.PageServer(page_dir)
    driver = pd.open_browser(WIDTH, HEIGHT)
    failures = 0
    tests = (("first frame", lambda: test_first_frame(driver, server.url, golden_dir, out_dir)),
             ("advances", lambda: test_advances(driver, server.url)),
             ("mu slider", lambda: test_mu_slider(driver, server.url)),
             ("screenshot download", lambda: test_screenshot_download(driver, server.url, out_dir)),
             ("touch tap", lambda: test_touch_tap(driver, server.url)))
    try:
        for name, run in tests:
            try:
                run()
                print(f"PASS {name}")
            except AssertionError as e:
                failures += 1
                print(f"FAIL {name}: {e}")
    finally:
        driver.quit()
        server.close()
    print(f"{len(tests) - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""A screenshot of the web page (docs/web.md) in headless Chromium, for the docs.

Usage: tests/web/page_screenshot.py OUT.png [--size 1366x768] [--steps 150] [--query ...]
                                   [--panel open|closed]
Opens the built page (build/web) playing, waits until `--steps` steps are done, then pauses
it (Space), opens or closes the panel if asked (a click on its Controls / Hide controls
button) and writes the viewport as a PNG.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import page_driver as pd  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--page-dir", default=os.path.join(os.path.dirname(__file__), "../../build/web"))
    parser.add_argument("--size", default="1366x768")
    parser.add_argument("--steps", type=int, default=150)
    parser.add_argument("--query", default="", help="extra URL query, e.g. n_seg=16")
    parser.add_argument("--panel", choices=("open", "closed"), help="as the page opens it if left out")
    args = parser.parse_args()
    missing = pd.missing_toolchain(args.page_dir)
    if missing:
        raise SystemExit(f"page_screenshot: {missing}")
    width, height = (int(v) for v in args.size.split("x"))
    server = pd.PageServer(args.page_dir)
    driver = pd.open_browser(width, height)
    try:
        driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                               {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
        driver.get(server.url + ("?" + args.query if args.query else ""))
        pd.wait_for(driver, lambda s: s["steps"] >= args.steps, f"{args.steps} steps", timeout=600,
                    stop_on_console_error=True)
        from selenium.webdriver.common.action_chains import ActionChains
        from selenium.webdriver.common.keys import Keys
        actions = ActionChains(driver)
        actions.key_down(Keys.SPACE).pause(0.3).key_up(Keys.SPACE).perform()
        pd.wait_for(driver, lambda s: not s["playing"], "the page to pause")
        state = pd.page_state(driver)
        if args.panel and ("panel" in state["widgets"]) != (args.panel == "open"):
            x0, y0, x1, y1 = state["widgets"]["panel_toggle"]
            pointer = ActionChains(driver)
            pointer.w3c_actions.pointer_action.move_to_location(int((x0 + x1) / 2), int((y0 + y1) / 2))
            pointer.w3c_actions.pointer_action.click()
            pointer.perform()
            pd.wait_for(driver, lambda s: ("panel" in s["widgets"]) == (args.panel == "open"),
                        f"the panel to be {args.panel}")
            # away from the button, so that no hover colour is in the picture
            pointer = ActionChains(driver)
            pointer.w3c_actions.pointer_action.move_to_location(width - 1, height - 1)
            pointer.perform()
        frames = pd.page_state(driver)["frames"]
        pd.wait_for(driver, lambda s: s["frames"] >= frames + 3, "a few paused frames")
        driver.save_screenshot(args.out)
        state = pd.page_state(driver)
        print(f"wrote {args.out}: {width}x{height}, step {state['steps']}, "
              f"min det F {state['min_det_f']:.3f}")
    finally:
        driver.quit()
        server.close()


if __name__ == "__main__":
    main()

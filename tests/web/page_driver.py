"""The web page (docs/web.md) in a real headless browser, for the tests and the speed
measurement in this folder.

Serves a page folder (build/web: index.html, index.js, index.wasm) on 127.0.0.1 at a free
port, from a thread of this process, and drives Debian's chromium through chromium-driver
and python3-selenium. WebGL 2 in headless Chromium is drawn by SwiftShader (a CPU
rasterizer), enabled with --enable-unsafe-swiftshader (Chromium otherwise refuses the
software fallback for WebGL).

`missing_toolchain(page_dir)` says what is missing (or "" when all is there), so callers
can skip with that message.
"""

import functools
import http.server
import json
import os
import shutil
import threading
import time

SKIP = 77  # the exit code ctest reads as "skipped" (SKIP_RETURN_CODE in CMakeLists.txt)


def missing_toolchain(page_dir):
    try:
        import selenium  # noqa: F401  (python3-selenium)
    except ImportError:
        return "python3-selenium is not installed (bash scripts/install-web-deps.sh)"
    try:
        import PIL  # noqa: F401  (python3-pil)
    except ImportError:
        return "python3-pil is not installed (bash scripts/install-web-deps.sh)"
    for program in ("chromium", "chromedriver"):
        if shutil.which(program) is None:
            return f"{program} is not installed (bash scripts/install-web-deps.sh)"
    if not os.path.isfile(os.path.join(page_dir, "index.html")):
        return (f"the page is not built: no {page_dir}/index.html "
                "(bash scripts/build-web.sh, after bash scripts/install-web-deps.sh)")
    return ""


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    extensions_map = dict(http.server.SimpleHTTPRequestHandler.extensions_map,
                          **{".wasm": "application/wasm", ".js": "text/javascript"})

    def log_message(self, *args):
        pass


class PageServer:
    """http.server on 127.0.0.1 only, at a port the system picks, in a daemon thread."""

    def __init__(self, page_dir):
        handler = functools.partial(_QuietHandler, directory=page_dir)
        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        self.url = f"http://127.0.0.1:{self.httpd.server_address[1]}/index.html"
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)
        self.thread.start()

    def close(self):
        self.httpd.shutdown()
        self.httpd.server_close()


def open_browser(width=1280, height=720):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium")
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                "--disable-gpu-vsync", "--hide-scrollbars", "--force-device-scale-factor=1",
                f"--window-size={width},{height}"):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)
    driver.set_page_load_timeout(60)
    return driver


def page_state(driver):
    """window.invfree as the page last published it (None before the first frame)."""
    text = driver.execute_script("return window.invfree ? JSON.stringify(window.invfree) : null;")
    return json.loads(text) if text else None


def wait_for(driver, predicate, what, timeout=60.0, stop_on_console_error=False):
    """Polls window.invfree until predicate(state) holds; raises naming `what` and the last
    state when it does not within `timeout` seconds (a hang guard, not a speed check).
    With stop_on_console_error, a console error (the page's program stopped: an uncaught
    exception or an abort, see shell.html) raises at once, with the page's status line."""
    deadline = time.monotonic() + timeout
    state = None
    while time.monotonic() < deadline:
        state = page_state(driver)
        if state and predicate(state):
            return state
        if stop_on_console_error:
            errors = console_errors(driver)
            if errors:
                status = driver.execute_script(
                    "const s = document.getElementById('status'); return s ? s.textContent : '';")
                raise AssertionError(f"console error while waiting for {what}: {errors}; "
                                     f"the page says: {status!r}")
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}; last window.invfree: {state}")


def console_errors(driver):
    """Console messages of level SEVERE (console.error, uncaught exceptions, failed loads)."""
    return [entry for entry in driver.get_log("browser") if entry.get("level") == "SEVERE"]

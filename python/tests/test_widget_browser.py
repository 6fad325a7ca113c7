"""The viewer in a real JupyterLab (from PyPI) in Debian's chromium through
chromedriver, as a user meets it: open a notebook, run it, see the image,
move the time slider and see the image change, click a pixel and see the
event its ray meets. Skipped without chromium and chromedriver, unless
VSTF_REQUIRE_BROWSER=1 (as .ci/run sets when it installed them)."""

import json
import os
import re
import shutil
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"


def browser_or_skip():
    found = shutil.which("chromium"), shutil.which("chromedriver")
    if all(found):
        return found
    if os.environ.get("VSTF_REQUIRE_BROWSER") == "1":
        pytest.fail("VSTF_REQUIRE_BROWSER=1 but chromium or chromedriver is missing")
    pytest.skip("no chromium and chromedriver (Debian: apt-get install chromium chromium-driver)")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def notebook(path):
    code = (
        "import vstf\n"
        f"viewer = vstf.Viewer(vstf.load({str(FIXTURES / 'flange.json')!r}), width=160, height=120)\n"
        "viewer"
    )
    book = {
        "cells": [{"cell_type": "code", "id": "viewer", "metadata": {}, "execution_count": None, "outputs": [], "source": code}],
        "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"}},
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    path.write_text(json.dumps(book))


@pytest.fixture
def lab(tmp_path):
    browser_or_skip()
    pytest.importorskip("jupyterlab")
    pytest.importorskip("selenium")
    notebook(tmp_path / "viewer.ipynb")
    port, token = free_port(), "vstf-test-token"
    # The notebook names its kernel; start it without asking, as a user's
    # "Always start the preferred kernel" does.
    settings = tmp_path / "lab-settings" / "@jupyterlab" / "notebook-extension"
    settings.mkdir(parents=True)
    (settings / "tracker.jupyterlab-settings").write_text('{"autoStartDefaultKernel": true}')
    env = dict(os.environ, JUPYTER_CONFIG_DIR=str(tmp_path / "config"), JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"),
               JUPYTERLAB_SETTINGS_DIR=str(tmp_path / "lab-settings"))
    server = subprocess.Popen(
        [sys.executable, "-m", "jupyterlab", "--no-browser", f"--port={port}", "--ip=127.0.0.1",
         f"--ServerApp.token={token}", f"--ServerApp.root_dir={tmp_path}", "--LabApp.expose_app_in_browser=True",
         "--ServerApp.disable_check_xsrf=False", "--LabApp.news_url=", "--allow-root"],
        env=env, stdout=subprocess.DEVNULL, stderr=open(tmp_path / "lab.log", "w"),
    )
    base = f"http://127.0.0.1:{port}"
    try:
        end = time.monotonic() + 90
        while True:
            try:
                urllib.request.urlopen(f"{base}/api/status?token={token}", timeout=2)
                break
            except OSError:
                if time.monotonic() > end or server.poll() is not None:
                    raise AssertionError("jupyter lab did not start: " + (tmp_path / "lab.log").read_text()[-2000:])
                time.sleep(0.3)
        yield f"{base}/lab/tree/viewer.ipynb?token={token}"
    finally:
        server.terminate()
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()


@pytest.fixture
def driver(tmp_path):
    chromium, chromedriver = browser_or_skip()
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for flag in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--no-first-run", "--window-size=1400,1000", f"--user-data-dir={tmp_path / 'chromium'}"]:
        options.add_argument(flag)
    d = webdriver.Chrome(service=Service(chromedriver), options=options)
    try:
        yield d
    finally:
        d.quit()


def until(d, script, seconds=120.0):
    """Waits until the JavaScript expression `script` is truthy; returns it."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        value = d.execute_script(f"return ({script});")
        if value:
            return value
        time.sleep(0.2)
    raise AssertionError(f"timed out waiting for {script}")


def test_the_viewer_in_jupyterlab(lab, driver):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    driver.get(lab)
    until(driver, "window.jupyterapp && document.querySelector('.jp-Notebook')")
    # Run the notebook once its kernel is idle, then wait for the viewer.
    until(driver, "window.jupyterapp.shell.currentWidget && window.jupyterapp.shell.currentWidget.sessionContext"
                  " && window.jupyterapp.shell.currentWidget.sessionContext.session"
                  " && window.jupyterapp.shell.currentWidget.sessionContext.session.kernel"
                  " && window.jupyterapp.shell.currentWidget.sessionContext.session.kernel.status === 'idle'")
    assert not driver.execute_script("return document.querySelector('.jp-Dialog')"), "a dialog asks something"
    driver.execute_script("window.jupyterapp.commands.execute('notebook:run-all-cells')")
    until(driver, "document.querySelector('.vstf-viewer canvas[data-frame]')")
    canvas = driver.find_element(By.CSS_SELECTOR, ".vstf-viewer canvas")
    first = canvas.get_attribute("data-frame")
    before = driver.execute_script("return arguments[0].toDataURL()", canvas)
    assert int(canvas.get_attribute("width")) == 160

    # Move the time slider as a user drags it: the image changes.
    driver.execute_script(
        "const s = document.querySelector('.vstf-viewer .vstf-time');"
        "s.value = s.max; s.dispatchEvent(new Event('input', {bubbles: true}));"
    )
    until(driver, f"document.querySelector('.vstf-viewer canvas').dataset.frame !== '{first}'")
    after = driver.execute_script("return arguments[0].toDataURL()", canvas)
    assert after != before

    # Click the middle of the image: the debug panel names what its ray meets.
    ActionChains(driver).move_to_element(canvas).click().perform()
    text = until(driver, "(t => t.includes('camera t') && t)(document.querySelector('.vstf-viewer .vstf-debug').textContent)")
    # The middle of the image (within the canvas's fractional placement).
    assert re.search(r"pixel (79|80), (59|60) at camera t", text), text
    assert "event seen: t = " in text and "object: " in text

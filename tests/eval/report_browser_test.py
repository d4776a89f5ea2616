#!/usr/bin/env python3
"""Opens report.html in a real browser (headless Chromium) and checks that every figure
and every link of it loads, that every figure is shown (not folded away), and that a
six-mode run's page reads at a glance: at most 4000 px tall at 1400 px wide.

The output directory is served on 127.0.0.1 (a free port); a checker page of the same
origin loads report.html in an iframe, waits for every <img> (complete, naturalWidth > 0),
fetches every <a href> (status 200, same origin: the report is offline) and writes its
verdict into its own DOM, which `chromium --dump-dom` prints. Then the checker is proved
to catch breakage: with one image and one linked file removed, it must report both.

  report_browser_test.py --lifelong build/apps/lifelong --scenario scenarios/corridor_3.yaml
  report_browser_test.py --report-dir runs/latest      # check an existing output directory

Exit status: 0 pass, 1 fail, 77 skip (no chromium; ctest's SKIP_RETURN_CODE).
"""
import argparse
import functools
import http.server
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading

SKIP = 77

CHECKER = """<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>report check</title></head><body>
<pre id="verdict">PENDING</pre>
<iframe id="report" src="REPORT" width="1400" height="1000"></iframe>
<script>
function done(result) {
  document.getElementById('verdict').textContent = 'VERDICT ' + JSON.stringify(result);
}
async function check() {
  const doc = document.getElementById('report').contentDocument;
  const images = Array.from(doc.images);
  await Promise.all(images.map(img => img.complete ? null : new Promise(resolve => {
    img.addEventListener('load', resolve);
    img.addEventListener('error', resolve);
  })));
  const problems = [];
  const hidden = [];
  for (const img of images) {
    if (!(img.complete && img.naturalWidth > 0)) problems.push('image ' + img.getAttribute('src'));
    const box = img.getBoundingClientRect();
    if (!(box.width > 0 && box.height > 0)) hidden.push(img.getAttribute('src'));
  }
  const height = doc.documentElement.scrollHeight;
  const sections = Array.from(doc.querySelectorAll('h2')).map(
      h => h.textContent + ' @' + Math.round(h.getBoundingClientRect().top));
  const links = Array.from(doc.querySelectorAll('a[href]'))
                     .filter(a => !a.getAttribute('href').startsWith('#'));
  for (const a of links) {
    const href = a.getAttribute('href');
    if (new URL(a.href).origin !== location.origin) { problems.push('external ' + href); continue; }
    try {
      const response = await fetch(a.href, {cache: 'no-store'});
      if (response.status !== 200) problems.push('link ' + href + ' ' + response.status);
    } catch (e) {
      problems.push('link ' + href + ' ' + e);
    }
  }
  done({title: doc.title, images: images.length, links: links.length, problems: problems,
        hidden: hidden, height: height, sections: sections});
}
document.getElementById('report').addEventListener('load', () => {
  check().catch(e => done({error: String(e)}));
});
</script></body></html>
"""


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def find_chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def browser_verdict(chromium, root, report_rel, tmp):
    """Serves `root`, loads the checker in Chromium, returns the parsed verdict."""
    with open(os.path.join(root, "check.html"), "w", encoding="utf-8") as f:
        f.write(CHECKER.replace("REPORT", report_rel))
    handler = functools.partial(QuietHandler, directory=root)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        profile = tempfile.mkdtemp(prefix="profile-", dir=tmp)  # a new, empty profile
        url = "http://127.0.0.1:%d/check.html" % server.server_address[1]
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
               "--no-first-run", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage",
               "--user-data-dir=" + profile,
               "--dump-dom", "--virtual-time-budget=10000", url]
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    finally:
        server.shutdown()
        server.server_close()
    match = re.search(r"VERDICT (\{.*?\})</pre>", out.stdout, re.S)
    if not match:
        raise RuntimeError("no verdict from chromium (exit %d)\nstdout: %s\nstderr: %s" %
                           (out.returncode, out.stdout[-2000:], out.stderr[-2000:]))
    return json.loads(match.group(1).replace("&quot;", '"').replace("&amp;", "&"))


SIX_MODES = "standard,pruned,pruned-exact,pruned-glc,pruned-nfr,pruned-naive"
MAX_HEIGHT_PX = 4000  # at 1400 px wide, six modes: the page reads at a glance


def run_lifelong(lifelong, scenario, out_dir):
    cmd = [lifelong, "run", scenario, "-o", out_dir, "--modes", SIX_MODES]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   timeout=600)


def expect(condition, message, failures):
    print(("ok    " if condition else "FAIL  ") + message)
    if not condition:
        failures.append(message)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lifelong", help="the lifelong binary (runs the scenario)")
    parser.add_argument("--scenario", help="scenario for `lifelong run`")
    parser.add_argument("--report-dir", help="check this output directory instead of a run")
    parser.add_argument("--keep", action="store_true", help="keep the temporary directory")
    args = parser.parse_args()
    chromium = find_chromium()
    if not chromium:
        print("SKIP: chromium not installed (scripts/install-deps.sh installs it)")
        return SKIP
    tmp = tempfile.mkdtemp(prefix="lifelong_report_browser_")
    failures = []
    try:
        if args.report_dir:
            root = os.path.abspath(args.report_dir)
            try:
                verdict = browser_verdict(chromium, root, "report.html", tmp)
            finally:
                os.remove(os.path.join(root, "check.html"))
            print(json.dumps(verdict, indent=1))
            expect(not verdict.get("error") and not verdict.get("problems"),
                   "every image and link of %s loads" % root, failures)
            expect(verdict.get("hidden") == [], "every figure is shown", failures)
            return 1 if failures else 0
        run_dir = os.path.join(tmp, "run")
        run_lifelong(args.lifelong, args.scenario, run_dir)
        verdict = browser_verdict(chromium, tmp, "run/report.html", tmp)
        print(json.dumps(verdict, indent=1))
        expect("error" not in verdict, "the checker ran in the browser", failures)
        expect(verdict.get("problems") == [], "every image and link loads", failures)
        # 8 plots, truth + 6 maps, 6 graphs; links: figures, CSVs, graphs, trajectories.
        expect(verdict.get("images", 0) >= 21, "21 or more images", failures)
        expect(verdict.get("links", 0) >= 60, "60 or more links", failures)
        expect(verdict.get("hidden") == [], "every figure is shown, none folded away", failures)
        expect(0 < verdict.get("height", 0) <= MAX_HEIGHT_PX,
               "six modes: the page is %s px tall at 1400 px wide, at most %d" %
               (verdict.get("height"), MAX_HEIGHT_PX), failures)

        # The checker must catch breakage: one image and one linked file gone.
        os.rename(os.path.join(run_dir, "nodes.png"), os.path.join(tmp, "nodes.png"))
        os.rename(os.path.join(run_dir, "pruned", "timeline.csv"),
                  os.path.join(tmp, "timeline.csv"))
        broken = browser_verdict(chromium, tmp, "run/report.html", tmp)
        problems = " | ".join(broken.get("problems", []))
        print("with nodes.png and pruned/timeline.csv removed: " + problems)
        expect("image nodes.png" in problems, "a missing image is reported", failures)
        expect("link pruned/timeline.csv 404" in problems, "a missing file is reported",
               failures)
    finally:
        if args.keep:
            print("kept " + tmp)
        else:
            shutil.rmtree(tmp, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

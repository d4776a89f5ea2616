#!/usr/bin/env python3
"""scripts/check_doc_links.py: on a made-up checkout it names a broken markdown link and a
broken HTML src by file and line and exits 1, and passes good ones, URLs and anchors; then
the real checkout's README and docs have no broken link."""
import os
import subprocess
import sys
import tempfile

ROOT = sys.argv[1]
SCRIPT = os.path.join(ROOT, "scripts", "check_doc_links.py")


def write(root, rel, text):
    path = os.path.join(root, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def run(root):
    return subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True)


def main():
    with tempfile.TemporaryDirectory() as d:
        write(d, "README.md", "[docs](docs/a.md) [web](https://example.org) [here](#top)\n")
        write(d, "docs/a.md", "intro\n[gone](b.md) and [fig](book/x.png)\n")
        write(d, "docs/book/x.png", "x")
        write(d, "docs/book/index.html", '<a href="x.png">x</a>\n<img src="cells/m.png">\n')
        out = run(d)
        assert out.returncode == 1, out
        lines = out.stdout.splitlines()
        assert sorted(lines) == [
            os.path.join("docs", "a.md") + ":2: b.md",
            os.path.join("docs", "book", "index.html") + ":2: cells/m.png",
        ], out.stdout
        write(d, "docs/b.md", "")
        write(d, "docs/book/cells/m.png", "")
        assert run(d).returncode == 0
    real = run(ROOT)
    assert real.returncode == 0, "broken links in the docs:\n" + real.stdout
    print("ok")


if __name__ == "__main__":
    main()

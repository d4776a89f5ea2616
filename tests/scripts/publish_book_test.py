#!/usr/bin/env python3
"""scripts/publish_book.py on a made-up book: the pages, the figures they show and the sweep
pages' own files are copied; a cell's report is not, and the sweep page's link to it keeps
its text only; a folder that is not an earlier copy is refused and left as it was."""
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(sys.argv[1], "scripts", "publish_book.py")


def write(root, rel, text):
    path = os.path.join(root, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def run(args):
    return subprocess.run([sys.executable, SCRIPT] + args, capture_output=True, text=True)


def files(root):
    return sorted(
        os.path.relpath(os.path.join(d, f), root) for d, _, fs in os.walk(root) for f in fs
    )


def main():
    with tempfile.TemporaryDirectory() as d:
        book, dest = os.path.join(d, "book"), os.path.join(d, "out")
        write(book, "results.md", "![a](sweep/a.png) [web](https://example.org) `sweep/`\n")
        write(book, "index.html", '<a href="sweep/report.html">s</a><img src="sweep/c1/m.png">')
        write(
            book,
            "sweep/report.html",
            '<a href="runs.csv">runs</a> <a href="c1/report.html">cell one</a>'
            '<img src="a.png"><a href="#top">top</a>',
        )
        for rel in ("sweep/a.png", "sweep/runs.csv", "sweep/c1/m.png", "sweep/c1/big.g2o"):
            write(book, rel, "x")
        write(book, "sweep/c1/report.html", '<a href="big.g2o">graph</a>')
        out = run([book, dest])
        assert out.returncode == 0, out.stderr
        assert files(dest) == [
            "index.html",
            "results.md",
            "sweep/a.png",
            "sweep/c1/m.png",
            "sweep/report.html",
            "sweep/runs.csv",
        ], files(dest)
        page = open(os.path.join(dest, "sweep", "report.html")).read()
        assert "cell one" in page and "c1/report.html" not in page, page
        assert '<a href="runs.csv">runs</a>' in page and 'href="#top"' in page, page
        # Run again: an earlier copy is replaced.
        assert run([book, dest]).returncode == 0
        # Anything else is refused and left as it was.
        other = os.path.join(d, "other")
        write(other, "keep.txt", "mine")
        refused = run([book, other])
        assert refused.returncode == 2 and "not replaced" in refused.stderr, refused.stderr
        assert files(other) == ["keep.txt"]
        assert run([other, os.path.join(d, "x")]).returncode == 2  # not a book
    print("ok")


if __name__ == "__main__":
    main()

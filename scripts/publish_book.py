#!/usr/bin/env python3
"""Copies the readable part of a `lifelong reproduce` book into a folder of its own (how
docs/book/quick/ is made), with no link left pointing at a file that was not copied.

Usage: scripts/publish_book.py BOOK_DIR DEST_DIR

Copied: results.md and index.html; every file they link or show (a sweep's report.html,
its figures); and every file those sweep pages link or show, except further HTML pages (a
cell's own report, with its maps, graphs and logs, stays in the book). A link to a file that
is not copied keeps its text and loses its target, so nothing in DEST_DIR points at a missing
file. DEST_DIR is replaced whole, if it is an earlier copy (it holds a results.md); any other
existing folder is refused (exit 2). Standard library only.
"""
import os
import re
import shutil
import sys

sys.dont_write_bytecode = True  # no __pycache__ beside the scripts
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_doc_links import local_links, local_target  # noqa: E402

ANCHOR = re.compile(r"""<a href="([^"]+)">(.*?)</a>""", re.S)
ROOTS = ("results.md", "index.html")


def links(book, page):
    """Book-relative targets of the local links of a page inside the book."""
    return [t for _, _, t in local_links(book, page) if not t.startswith("..")]


def select(book):
    """Book-relative paths to copy."""
    chosen = {r for r in ROOTS if os.path.exists(os.path.join(book, r))}
    pages = list(chosen)
    for depth in (1, 2):
        next_pages = []
        for page in pages:
            for target in links(book, page):
                if target in chosen or not os.path.isfile(os.path.join(book, target)):
                    continue
                if target.endswith(".html") and depth == 2:
                    continue  # a cell's own report stays in the book
                chosen.add(target)
                if target.endswith((".html", ".md")):
                    next_pages.append(target)
        pages = next_pages
    return chosen


def unlink_missing(dest, page, chosen):
    path = os.path.join(dest, page)
    with open(path, encoding="utf-8") as f:
        text = f.read()

    def keep(m):
        target = local_target(page, m.group(1))
        return m.group(0) if target is None or target in chosen else m.group(2)

    with open(path, "w", encoding="utf-8") as f:
        f.write(ANCHOR.sub(keep, text))


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    book, dest = argv[1], argv[2]
    if not os.path.isfile(os.path.join(book, "results.md")):
        sys.stderr.write(f"{book}: no results.md (is it a `lifelong reproduce` book?)\n")
        return 2
    if os.path.exists(dest) and not os.path.isfile(os.path.join(dest, "results.md")):
        sys.stderr.write(f"{dest}: exists and holds no results.md; not replaced\n")
        return 2
    chosen = select(book)
    if os.path.exists(dest):
        shutil.rmtree(dest)
    for rel in sorted(chosen):
        os.makedirs(os.path.dirname(os.path.join(dest, rel)) or dest, exist_ok=True)
        shutil.copy(os.path.join(book, rel), os.path.join(dest, rel))
    for rel in chosen:
        if rel.endswith(".html"):
            unlink_missing(dest, rel, chosen)
    print(f"{len(chosen)} files from {book} in {dest}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

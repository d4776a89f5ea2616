#!/usr/bin/env python3
"""Every relative link of the docs resolves: README.md, docs/**/*.md and the HTML pages under
docs/ (markdown `](target)`, HTML href= and src=). URLs, in-page anchors and absolute paths
are not checked. Prints each broken link as FILE:LINE: target, and exits 1 if any.

Usage: scripts/check_doc_links.py [CHECKOUT]   (default: the current directory)
"""
import os
import re
import sys

MD = re.compile(r"\]\(([^)\s]+)\)")
HTML = re.compile(r"""(?:href|src)="([^"]+)\"""")


def local_target(page, link):
    """The checkout- or book-relative path a link of `page` points at, or None for a URL,
    an in-page anchor or an absolute path."""
    if re.match(r"^[a-z]+:", link) or link.startswith(("#", "/")):
        return None
    return os.path.normpath(os.path.join(os.path.dirname(page), link.split("#")[0]))


def local_links(root, page):
    """(line number, link as written, target) of each local link of a .md or .html page."""
    pattern = MD if page.endswith(".md") else HTML
    with open(os.path.join(root, page), encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            for link in pattern.findall(line):
                target = local_target(page, link)
                if target is not None:
                    yield number, link, target


def pages(root):
    yield "README.md"
    for d, _, files in os.walk(os.path.join(root, "docs")):
        for f in sorted(files):
            if f.endswith((".md", ".html")):
                yield os.path.relpath(os.path.join(d, f), root)


def broken(root, page):
    for number, link, target in local_links(root, page):
        if not os.path.exists(os.path.join(root, target)):
            yield number, link


def main(argv):
    root = argv[1] if len(argv) > 1 else "."
    bad = [(p, n, link) for p in pages(root) for n, link in broken(root, p)]
    for p, n, link in bad:
        print(f"{p}:{n}: {link}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

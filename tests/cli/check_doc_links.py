#!/usr/bin/env python3
"""Checks the documentation's relative links: every link and image in README.md and
docs/**/*.md that is not a URL must name a file or folder of the repository, and a
#fragment into a Markdown file must name one of its headings (GitHub's anchors). Code
blocks and code spans are not links. Prints each broken link as FILE:LINE: ... and exits 1
when there is one. Run by tests/cli/docs_test.cpp; usage: check_doc_links.py [REPO_ROOT]."""
import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
HTML_ANCHOR = re.compile(r"<a\s+(?:name|id)=\"([^\"]+)\"")


def prose_lines(text):
    """(line number, line) outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(text.split("\n"), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def without_code_spans(line):
    return re.sub(r"(`+)(?:(?!\1).)+?\1", lambda m: " " * len(m.group(0)), line)


def slug(heading):
    """GitHub's anchor of a heading: lower case, markup and punctuation dropped (letters,
    digits, '_', '-' and spaces kept), each space a '-'."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text
    text = re.sub(r"<[^>]+>", "", text)  # inline HTML
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in "_- ")
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, result = {}, set()
        with open(path, encoding="utf-8") as f:
            for _, line in prose_lines(f.read()):
                for name in HTML_ANCHOR.findall(line):
                    result.add(name)
                m = HEADING.match(line)
                if not m:
                    continue
                base = slug(m.group(2))
                n = seen.get(base, 0)
                seen[base] = n + 1
                result.add(base if n == 0 else "%s-%d" % (base, n))
        cache[path] = result
    return cache[path]


def documents(root):
    yield os.path.join(root, "README.md")
    for folder, dirs, files in os.walk(os.path.join(root, "docs")):
        dirs.sort()
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(folder, name)


def check(root):
    broken, links = [], 0
    for doc in documents(root):
        with open(doc, encoding="utf-8") as f:
            text = f.read()
        where = os.path.relpath(doc, root)
        for number, line in prose_lines(text):
            for target in LINK.findall(without_code_spans(line)):
                if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):  # http:, mailto:, ...
                    continue
                links += 1
                path, _, fragment = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
                if not os.path.exists(resolved):
                    broken.append("%s:%d: %s: no such file" % (where, number, target))
                elif not os.path.realpath(resolved).startswith(os.path.realpath(root) + os.sep):
                    broken.append("%s:%d: %s: outside the repository" % (where, number, target))
                elif fragment and resolved.endswith(".md") and fragment not in anchors(resolved):
                    broken.append("%s:%d: %s: no heading #%s in %s"
                                  % (where, number, target, fragment, os.path.relpath(resolved, root)))
    return broken, links


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), "..", ".."))
    broken, links = check(root)
    for line in broken:
        print(line)
    print("%d relative links checked, %d broken" % (links, len(broken)))
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())

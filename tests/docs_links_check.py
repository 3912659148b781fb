#!/usr/bin/env python3
"""Every relative link in the project's Markdown resolves: the file exists and, for `file#anchor`
or `#anchor`, the target file has a heading with that GitHub-style anchor. Links inside fenced
code blocks and inline code are not links; http(s) and mailto links are not checked (no network).
Usage: docs_links_check.py SOURCE_DIR   (first checks itself on a made-up tree with known answers)"""
import os
import re
import sys

SKIP_DIRS = {"out", "cache", "node_modules", "shared"}
LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def markdown_files(root):
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith((".", "build")) and d not in SKIP_DIRS)
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(folder, name)


def prose_lines(path):
    """(line number, text) outside fenced code blocks, with inline code removed."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if line.lstrip().startswith(("```", "~~~")):
                fenced = not fenced
                continue
            if not fenced:
                yield number, re.sub(r"`[^`]*`", "", line)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading).replace("`", "").lower()
    return "".join(c for c in text if c.isalnum() or c in " -_").replace(" ", "-")


def dead_links(root):
    bad, checked = [], 0
    for path in markdown_files(root):
        for number, line in prose_lines(path):
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                checked += 1
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                where = f"{os.path.relpath(path, root)}:{number}: {target}"
                if not os.path.exists(dest):
                    bad.append(f"{where}: no such file")
                elif anchor and dest.endswith(".md") and anchor not in raw_anchors(dest):
                    bad.append(f"{where}: no heading with anchor #{anchor} in {os.path.relpath(dest, root)}")
    return bad, checked


def self_check():
    """The checker on a tree with known answers, so that a checker that finds nothing fails."""
    import tempfile
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "docs"))
        with open(os.path.join(root, "docs", "a.md"), "w", encoding="utf-8") as f:
            f.write("# Scale-out: Slurm and `GNU` parallel\n## Twice\n## Twice\n```\n[x](fenced.md)\n```\n"
                    "`[y](code.md)`\n")
        with open(os.path.join(root, "README.md"), "w", encoding="utf-8") as f:
            f.write("[ok](docs/a.md#scale-out-slurm-and-gnu-parallel) [ok](docs/a.md#twice-1) "
                    "[web](https://example.org/x.md) ![img](docs/a.md)\n"
                    "[dead file](docs/b.md) [dead anchor](docs/a.md#twice-2) [self](#nothing)\n")
        bad, checked = dead_links(root)
        found = sorted(b.split(": ")[1] for b in bad)
        expected = sorted(["#nothing", "docs/a.md#twice-2", "docs/b.md"])
        if checked != 6 or found != expected:
            print(f"FAIL: the checker itself: {checked} links checked (6 expected), dead {found} ({expected} expected)")
            return False
    return True


def main():
    if not self_check():
        return 1
    bad, checked = dead_links(os.path.abspath(sys.argv[1]))
    for line in bad:
        print("FAIL: " + line)
    print(f"{checked} relative links checked, {len(bad)} dead")
    return 1 if bad else 0


def raw_anchors(path, cache={}):
    """Anchors of the headings as written (inline code in a heading is part of its anchor)."""
    if path not in cache:
        found, seen, fenced = set(), {}, False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith(("```", "~~~")):
                    fenced = not fenced
                    continue
                m = None if fenced else HEADING.match(line)
                if m:
                    base = slug(m.group(2))
                    n = seen.get(base, 0)
                    seen[base] = n + 1
                    found.add(base if n == 0 else f"{base}-{n}")
        cache[path] = found
    return cache[path]


if __name__ == "__main__":
    sys.exit(main())

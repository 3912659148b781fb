#!/usr/bin/env python3
"""What the documentation says a reader can use and cite:
- it speaks of the software, not of its making: no design-note section numbers ("SPEC §"), work
  sessions, issue numbers, clock times or branch and co-worker asides in the Markdown pages, the
  presets' and scenes' comments, or the comments of denoise/ and training/ (code spans and fenced
  blocks are quoted output, not prose, and are skipped);
- every subcommand of the binary has a row in docs/usage.md's command table whose synopsis shows
  `-c FILE` exactly when `fovrt CMD --help` lists -c,--config, and the sentences of README.md and
  usage.md that name the commands taking `-c FILE` name exactly those; README's documentation
  table lists every subcommand;
- LICENSE, CITATION.cff and docs/papers.bib exist, hold what a citation needs, and README links them.
Usage: docs_text_check.py SOURCE_DIR FOVRT_BINARY   (first checks itself on made-up text)"""
import glob
import os
import re
import subprocess
import sys

MAKING_OF = re.compile(r"SPEC §|SPEC section|session [0-9]|stop [0-9]+|issue #|[0-9]{2}:[0-9]{2} UTC|"
                       r"other engineers|this branch")
# Pages left out of the check (none: every page is held to it).
PENDING_PAGES: set[str] = set()
SKIP_DIRS = {"out", "cache", "node_modules", "shared"}
PAPERS = ["schied2017svgf", "schied2018asvgf", "tu2024twohistory", "zhuang2021brdfdemodulation",
          "chaitanya2017rae", "mantiuk2021fovvideovdp"]


def prose_lines(text, comment=None):
    """(line number, prose) of Markdown (comment None: outside fences, code spans removed) or of
    source whose comments start with `comment`."""
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if comment is None:
            if line.lstrip().startswith(("```", "~~~")):
                fenced = not fenced
            elif not fenced:
                yield number, re.sub(r"`[^`]*`", "", line)
        elif comment in line:
            yield number, line[line.index(comment):]


def making_of(text, comment=None):
    return [(n, m.group(0)) for n, line in prose_lines(text, comment) for m in [MAKING_OF.search(line)] if m]


def documents(root):
    """(relative path, comment marker) of every text the making-of check reads."""
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith((".", "build")) and d not in SKIP_DIRS)
        for name in sorted(files):
            rel = os.path.relpath(os.path.join(folder, name), root)
            if name.endswith(".md") and rel not in PENDING_PAGES:
                yield rel, None
    for pattern, comment in [("presets/*.toml", "#"), ("scenes/*.toml", "#"), ("training/*.py", "#"),
                             ("denoise/**/*.h", "//"), ("denoise/**/*.cpp", "//")]:
        for path in sorted(glob.glob(os.path.join(root, pattern), recursive=True)):
            yield os.path.relpath(path, root), comment


def check_making_of(root):
    bad = []
    for rel, comment in documents(root):
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            text = f.read()
        if rel.endswith(".py"):  # docstrings are prose too
            text = re.sub(r'"""(.*?)"""', lambda m: "# " + m.group(1).replace("\n", "\n# "), text, flags=re.S)
        bad += [f"{rel}:{n}: '{found}' (say what the software does, cite the paper or a docs page)"
                for n, found in making_of(text, comment)]
    return bad


def help_text(binary, *args):
    run = subprocess.run([binary, *args, "--help"], capture_output=True, text=True)
    return run.stdout + run.stderr


def subcommands(binary):
    text = help_text(binary)
    block = text.split("Subcommands:", 1)[1] if "Subcommands:" in text else ""
    return [m.group(1) for m in re.finditer(r"^  ([a-z][a-z0-9-]*)\s", block, re.M)]


def named_commands(sentence):
    return set(re.findall(r"`([a-z][a-z0-9-]*)`", sentence))


def config_sentences(readme, usage):
    """The command names of README's and usage.md's sentences about `-c FILE` (None: not found)."""
    flat = lambda text: re.sub(r"\s+", " ", text)
    r = re.search(r"((?:`[a-z-]+`(?:, | and ))+`[a-z-]+`) take a TOML config \(`-c FILE`\)", flat(readme))
    u = re.search(r"`-c FILE` \((?:[^()]|\([^)]*\))*\) is an option of ((?:`[a-z-]+`(?:, | and ))+`[a-z-]+`)", flat(usage))
    return (named_commands(r.group(1)) if r else None, named_commands(u.group(1)) if u else None)


def usage_rows(usage):
    """First cell of each command-table row: {command: [synopses]}."""
    rows = {}
    for m in re.finditer(r"^\| `fovrt ([a-z][a-z0-9-]*)([^`]*)` \|", usage, re.M):
        rows.setdefault(m.group(1), []).append(m.group(2))
    return rows


def check_commands(root, binary):
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    with open(os.path.join(root, "docs", "usage.md"), encoding="utf-8") as f:
        usage = f.read()
    commands = subcommands(binary)
    if len(commands) < 5:
        return [f"`{binary} --help` lists {len(commands)} subcommands; cannot check the command docs"]
    takes_config = {c for c in commands if "-c,--config" in help_text(binary, c)}
    bad, rows = [], usage_rows(usage)
    for c in commands:
        if c not in rows:
            bad.append(f"docs/usage.md: no row `fovrt {c} …` in the command table")
        for synopsis in rows.get(c, []):
            if ("-c FILE" in synopsis) != (c in takes_config):
                bad.append(f"docs/usage.md: row `fovrt {c}{synopsis}` "
                           f"{'shows' if c not in takes_config else 'lacks'} -c FILE; `fovrt {c} --help` "
                           f"{'has no' if c not in takes_config else 'has'} -c,--config")
    in_readme, in_usage = config_sentences(readme, usage)
    for where, named in [("README.md", in_readme), ("docs/usage.md", in_usage)]:
        if named is None:
            bad.append(f"{where}: no sentence naming the commands that take `-c FILE`")
        elif named != takes_config:
            bad.append(f"{where}: names {sorted(named)} as taking -c FILE; the binary: {sorted(takes_config)}")
    doc_row = next((l for l in readme.splitlines() if l.startswith("| [docs/usage.md]")), "")
    bad += [f"README.md: the docs table's usage.md row does not list `{c}`"
            for c in commands if f"`{c}`" not in doc_row]
    return bad


def check_citation(root):
    bad = []
    def read(rel):
        path = os.path.join(root, rel)
        if not os.path.exists(path):
            bad.append(f"{rel}: missing")
            return ""
        with open(path, encoding="utf-8") as f:
            return f.read()
    licence, cff, bib, readme = read("LICENSE"), read("CITATION.cff"), read("docs/papers.bib"), read("README.md")
    if licence and not ("MIT License" in licence and "Copyright (c) 2026 the fovrt authors" in licence):
        bad.append("LICENSE: not the MIT licence of the fovrt authors")
    for key in ["cff-version: 1.2.0", "title:", 'name: "the fovrt authors"', "license: MIT", "preferred-citation:"]:
        if cff and key not in cff:
            bad.append(f"CITATION.cff: no `{key}`")
    if bib and re.sub(r"(?m)^%.*$", "", bib).count("{") != re.sub(r"(?m)^%.*$", "", bib).count("}"):
        bad.append("docs/papers.bib: unbalanced braces")
    entries = dict(re.findall(r"@\w+\{(\w+),(.*?)\n\}", bib, re.S))
    for key in PAPERS:
        if bib and not (key in entries and re.search(r"\btitle\s*=", entries[key]) and re.search(r"\byear\s*=", entries[key])):
            bad.append(f"docs/papers.bib: no entry {key} with a title and a year")
    for link in ["(LICENSE)", "(CITATION.cff)", "(docs/papers.bib)"]:
        if link not in readme:
            bad.append(f"README.md: no link {link}")
    return bad


def self_check():
    """The checks on made-up text with known answers, so that a checker that finds nothing fails."""
    md = "# T\nSee SPEC §3 and issue #4.\n`SPEC §5 in code`\n```\nstarted 14:44 UTC\n```\nok at 10:00 UTC\n"
    src = "int a; // (SPEC §12)\nint b = 3; // Schied et al. 2017, §4\n"
    readme = "`run`, `xr` and `config` take a TOML config\n(`-c FILE`) and more."
    usage = ("| `fovrt run [-c FILE]` | x |\n| `fovrt vdp A B` | y |\n"
             "`-c FILE` (a config, [below](#c)) is an option of `run`,\n`xr` and `config`; others not.")
    found = ([n for n, _ in making_of(md)], [n for n, _ in making_of(src, "//")],
             config_sentences(readme, usage), usage_rows(usage))
    expected = ([2, 7], [1], ({"run", "xr", "config"}, {"run", "xr", "config"}),
                {"run": [" [-c FILE]"], "vdp": [" A B"]})
    if found != expected:
        print(f"FAIL: the checker itself: found {found}, expected {expected}")
        return False
    return True


def main():
    if len(sys.argv) != 3:
        print("usage: docs_text_check.py SOURCE_DIR FOVRT_BINARY")
        return 2
    if not self_check():
        return 1
    root, binary = os.path.abspath(sys.argv[1]), sys.argv[2]
    bad = check_making_of(root) + check_commands(root, binary) + check_citation(root)
    for line in bad:
        print("FAIL: " + line)
    print(f"documentation text: {len(bad)} problem(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""No source file includes a header from its own floor's other folders or from a higher floor.
The floors are the table under "## Floors" in docs/ARCHITECTURE.md (floor number, the folders on
it): a file in folder f on floor n may include `"x/..."` only where x is f or on a floor below n. Scans every .h, .cpp,
.glsl and .comp under src/, denoise/, foveation/, gaze/ and shaders/; an include whose first
component names no floor's folder (a system header, a shader's own `common/...`) is not checked,
and a scanned folder the table does not place is an error, so a new folder must be given a floor.
Usage: include_floors_check.py SOURCE_DIR   (first checks itself on a made-up tree with known answers)"""
import os
import re
import sys
import tempfile

SCANNED = ("src", "denoise", "foveation", "gaze", "shaders")
EXTENSIONS = (".h", ".cpp", ".glsl", ".comp")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_]+)/')
FLOOR_ROW = re.compile(r"^\|\s*(\d+)\s*\|([^|]*)\|")


def read_floors(doc):
    """{folder: floor} from the table under "## Floors"."""
    floors = {}
    in_section = False
    with open(doc, encoding="utf-8") as f:
        for line in f:
            if line.startswith("## "):
                in_section = line.strip() == "## Floors"
                continue
            m = FLOOR_ROW.match(line) if in_section else None
            if m:
                for folder in re.findall(r"`([^`]+)`", m.group(2)):
                    floors[folder.strip("/").split("/")[-1]] = int(m.group(1))
    if not floors:
        sys.exit(f"{doc}: no '## Floors' table (| floor | `folder` ... |)")
    return floors


def folder_of(root, path):
    """The folder a file belongs to: src/<folder>/..., else the top-level folder (denoise/...)."""
    parts = os.path.relpath(path, root).split(os.sep)
    return parts[1] if parts[0] == "src" else parts[0]


def violations(root, floors):
    found = []
    for top in SCANNED:
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            dirs.sort()
            for name in sorted(files):
                if not name.endswith(EXTENSIONS):
                    continue
                path = os.path.join(folder, name)
                if os.path.dirname(path) == os.path.join(root, "src"):
                    continue  # no source lives directly in src/
                owner = folder_of(root, path)
                if owner not in floors:
                    found.append(f"{os.path.relpath(path, root)}: folder '{owner}' has no floor in the table")
                    continue
                with open(path, encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        target = m.group(1) if m else None
                        if target in floors and target != owner and floors[target] >= floors[owner]:
                            found.append(f"{os.path.relpath(path, root)}:{number}: {owner} (floor {floors[owner]}) "
                                         f"includes {target}/ (floor {floors[target]})")
    return found


def self_check():
    """A made-up tree: includes of its own folder, down, sideways, up, third-party; an unplaced folder."""
    with tempfile.TemporaryDirectory() as root:
        files = {
            "docs/ARCHITECTURE.md": "## Floors\n\n| floor | folders |\n|---|---|\n| 0 | `core` |\n"
                                    "| 1 | `src/lib`, `gaze` |\n| 2 | `app` |\n\n## Next\n| 9 | `core` |\n",
            "src/core/a.h": '#include "core/b.h"\n',
            "src/lib/l.cpp": '#include "core/a.h"\n#include "gaze/g.h"\n#include <vector>\n',
            "gaze/g.h": '#include "CLI/CLI.hpp"\n  #  include "app/x.h"\n',
            "src/app/x.h": '#include "lib/l.h"\n',
            "src/stray/s.h": "\n",
        }
        for rel, text in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
            with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
                f.write(text)
        floors = read_floors(os.path.join(root, "docs/ARCHITECTURE.md"))
        assert floors == {"core": 0, "lib": 1, "gaze": 1, "app": 2}, floors
        got = sorted(violations(root, floors))
        want = ["gaze/g.h:2: gaze (floor 1) includes app/ (floor 2)",
                "src/lib/l.cpp:2: lib (floor 1) includes gaze/ (floor 1)",
                "src/stray/s.h: folder 'stray' has no floor in the table"]
        assert got == want, got


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    self_check()
    root = sys.argv[1]
    floors = read_floors(os.path.join(root, "docs", "ARCHITECTURE.md"))
    found = violations(root, floors)
    for line in found:
        print(line)
    if found:
        print(f"{len(found)} include(s) of a higher floor or of a folder on the same floor "
              "(docs/ARCHITECTURE.md, ## Floors)")
        return 1
    print(f"include floors: {len(set(floors.values()))} floors, {len(floors)} folders, every include downward")
    return 0


if __name__ == "__main__":
    sys.exit(main())

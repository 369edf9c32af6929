#!/usr/bin/python3
"""CTest test `layer_map_matches_targets`: the layer map (docs/architecture.md) is the build's.

usage: check_layer_map.py PROJECT_ROOT

src/CMakeLists.txt declares one target per area of src/rayint/ with the areas it links
(`rayint_area(NAME DEPS a b ...)`); an area sees only those headers, so that list is the layering.
This fails with one line per difference when
  - a folder of src/rayint/ is not declared as an area (its includes would not be checked), or
  - the table between the markers `<!-- layer-map -->` and `<!-- /layer-map -->` in docs/architecture.md
    does not name every area once with exactly the areas it links (column "links").
"""
import os
import re
import sys


def declared_areas(root):
    text = open(os.path.join(root, "src", "CMakeLists.txt")).read()
    text = re.sub(r"#[^\n]*", "", text)
    areas = {}
    for m in re.finditer(r"rayint_area\(\s*(\w+)([^)]*)\)", text):
        name, rest = m.group(1), m.group(2).split()
        deps, on = [], False
        for word in rest:
            if word in ("DEPS", "PUBLIC_LIBS", "PRIVATE_LIBS"):
                on = word == "DEPS"
            elif on:
                deps.append(word)
        areas[name] = set(deps)
    return areas


def readme_map(root):
    text = open(os.path.join(root, "docs", "architecture.md")).read()
    m = re.search(r"<!-- layer-map -->(.*?)<!-- /layer-map -->", text, re.S)
    if not m:
        return None
    rows = {}
    for line in m.group(1).splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 3 or not cells[0].startswith("`"):
            continue
        name = cells[0].strip("`").rstrip("/")
        links = set(re.findall(r"`?(\w+)`?", cells[-1])) - {"none"}
        if name in rows:
            rows[name] = None  # named twice
        else:
            rows[name] = links
    return rows


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: check_layer_map.py PROJECT_ROOT")
    root = argv[1]
    areas = declared_areas(root)
    problems = []
    folders = sorted(d for d in os.listdir(os.path.join(root, "src", "rayint"))
                     if os.path.isdir(os.path.join(root, "src", "rayint", d)))
    for d in folders:
        if d not in areas:
            problems.append(f"src/rayint/{d}/ is not an area target in src/CMakeLists.txt")
    rows = readme_map(root)
    if rows is None:
        problems.append("docs/architecture.md has no <!-- layer-map --> table")
        rows = {}
    for name, deps in sorted(areas.items()):
        if name not in rows:
            problems.append(f"docs/architecture.md layer map: area {name} is missing")
        elif rows[name] is None:
            problems.append(f"docs/architecture.md layer map: area {name} is named twice")
        elif rows[name] != deps:
            problems.append(f"docs/architecture.md layer map: {name} links {sorted(deps)} in src/CMakeLists.txt, "
                            f"docs/architecture.md says {sorted(rows[name])}")
    for name in sorted(set(rows) - set(areas)):
        problems.append(f"docs/architecture.md layer map: {name} is no area of src/CMakeLists.txt")
    for p in problems:
        print("layer map: " + p)
    if problems:
        sys.exit(1)
    print(f"layer map: {len(areas)} areas, docs/architecture.md and src/CMakeLists.txt agree")


if __name__ == "__main__":
    main(sys.argv)

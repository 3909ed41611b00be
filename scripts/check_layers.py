#!/usr/bin/env python3
"""Checks the include graph of the folders against the layer picture in docs/architecture.md.

Every `#include "folder/..."` line in a layer's sources is an edge layer -> folder. The check fails when an
edge is not drawn in the picture's mermaid graph, or when a drawn edge has no include behind it. tests/ and
examples/ may include anything.
"""
import argparse
import pathlib
import re
import sys

FREE = {"tests", "examples"}
SOURCES = {".hpp", ".cpp", ".h", ".cc"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')
EDGE = re.compile(r"^\s*([a-z_]+)\s*-->\s*([a-z_]+)\s*$")


def drawn_edges(doc: pathlib.Path):
    text = doc.read_text(encoding="utf-8")
    block = re.search(r"```mermaid\n(.*?)```", text, re.S)
    if not block:
        sys.exit(f"check_layers: no mermaid graph in {doc}")
    return {m.groups() for line in block.group(1).splitlines() if (m := EDGE.match(line))}


def include_edges(root: pathlib.Path, layers):
    edges = {}
    for layer in layers:
        for path in sorted((root / layer).rglob("*")):
            if path.suffix not in SOURCES or not path.is_file():
                continue
            for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
                m = INCLUDE.match(line)
                if m and m.group(1) != layer and (root / m.group(1)).is_dir():
                    edges.setdefault((layer, m.group(1)), f"{path.relative_to(root)}:{number}")
    return edges


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", default=".", help="repository root [default .]")
    args = parser.parse_args()
    root = pathlib.Path(args.root)
    drawn = drawn_edges(root / "docs" / "architecture.md")
    layers = sorted({a for a, _ in drawn} | {b for _, b in drawn})
    found = include_edges(root, layers)
    wrong = sorted(e for e in found if e not in drawn)
    unused = sorted(e for e in drawn if e not in found)
    for (a, b), where in sorted(found.items()):
        print(f"{a} -> {b}   e.g. {where}")
    for a, b in wrong:
        print(f"FAIL: {a}/ includes {b}/ ({found[(a, b)]}), an arrow docs/architecture.md does not draw")
    for a, b in unused:
        print(f"FAIL: docs/architecture.md draws {a} --> {b}, but no file of {a}/ includes {b}/")
    if wrong or unused:
        return 1
    print(f"PASS: {len(found)} include edges between {len(layers)} layers, all drawn, every arrow used")
    return 0


if __name__ == "__main__":
    sys.exit(main())

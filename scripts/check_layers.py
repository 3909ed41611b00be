#!/usr/bin/env python3
"""Checks the include graph of the folders against the layer picture in docs/architecture.md.

Every `#include "folder/..."` line in a layer's sources is an edge layer -> folder. The check fails when an
edge is not drawn in the picture's mermaid graph, or when a drawn edge has no include behind it. tests/ and
examples/ may include anything.

A layer is a top-level folder, or a subfolder the graph declares as a node of its own with its path as the
label, e.g. `main_job["schedulers/main_job"]`: its files then belong to it and not to the folder above, and an
include of a file under it is an edge to it.
"""
import argparse
import pathlib
import re
import sys

FREE = {"tests", "examples"}
SOURCES = {".hpp", ".cpp", ".h", ".cc"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+/[^"]*)"')
EDGE = re.compile(r"^\s*([a-z_]+)\s*-->\s*([a-z_]+)\s*$")
NODE = re.compile(r'^\s*([a-z_]+)\["?([a-z_/]+)"?\]\s*$')


def picture(doc: pathlib.Path):
    """The drawn edges, and every layer's folder (the node's label where it declares one, else its name)."""
    text = doc.read_text(encoding="utf-8")
    block = re.search(r"```mermaid\n(.*?)```", text, re.S)
    if not block:
        sys.exit(f"check_layers: no mermaid graph in {doc}")
    lines = block.group(1).splitlines()
    edges = {m.groups() for line in lines if (m := EDGE.match(line))}
    folders = {a: a for edge in edges for a in edge}
    folders.update({m.group(1): m.group(2) for line in lines if (m := NODE.match(line))})
    return edges, folders


def layer_of(relative: str, folders):
    """The layer whose folder is the longest prefix of a repository-relative path (None: no layer's)."""
    best = None
    for layer, folder in folders.items():
        if relative.startswith(folder + "/") and (best is None or len(folder) > len(folders[best])):
            best = layer
    return best


def include_edges(root: pathlib.Path, folders):
    edges = {}
    tops = sorted({folder.split("/")[0] for folder in folders.values()})
    for path in sorted(p for top in tops for p in (root / top).rglob("*")):
        if path.suffix not in SOURCES or not path.is_file():
            continue
        relative = path.relative_to(root).as_posix()
        layer = layer_of(relative, folders)
        if layer is None:
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m or not (root / m.group(1).split("/")[0]).is_dir():
                continue
            target = layer_of(m.group(1), folders)
            if target is not None and target != layer:
                edges.setdefault((layer, target), f"{relative}:{number}")
    return edges


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", default=".", help="repository root [default .]")
    args = parser.parse_args()
    root = pathlib.Path(args.root)
    drawn, folders = picture(root / "docs" / "architecture.md")
    layers = sorted(folders)
    found = include_edges(root, folders)
    wrong = sorted(e for e in found if e not in drawn)
    unused = sorted(e for e in drawn if e not in found)
    for (a, b), where in sorted(found.items()):
        print(f"{a} -> {b}   e.g. {where}")
    for a, b in wrong:
        print(f"FAIL: {folders[a]}/ includes {folders[b]}/ ({found[(a, b)]}), an arrow docs/architecture.md does not draw")
    for a, b in unused:
        print(f"FAIL: docs/architecture.md draws {a} --> {b}, but no file of {folders[a]}/ includes {folders[b]}/")
    if wrong or unused:
        return 1
    print(f"PASS: {len(found)} include edges between {len(layers)} layers, all drawn, every arrow used")
    return 0


if __name__ == "__main__":
    sys.exit(main())

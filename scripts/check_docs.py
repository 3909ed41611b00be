#!/usr/bin/env python3
"""Checks that the docs cannot rot: every relative link resolves, and every command in a ```sh block is one
the code still accepts.

For each command of a shell block (lines joined at a trailing backslash, split at && || ; |, comments and
environment assignments dropped):
  - a frontsteal program or benchmark under ./build/<preset>/: when built in --build, it must answer --help
    (after its subcommand, if the command gives one) with exit status 0, and every --flag the command uses
    must appear in that help; when not built (another preset), its name must be an add_executable target;
  - cmake / ctest: every --preset must exist in CMakePresets.json; ctest -R REGEX / -L LABEL must select at
    least one test of --build;
  - a script of the repository (scripts/*.py, *.sh): the file must exist.
And every `folder/path` written in backticks outside code blocks whose first folder is a folder of the
repository (core/, docs/, schedulers/ ...; not out/ or build/, which runs write) must exist, as a file, a
folder, or a glob.
Usage: check_docs.py --build build/release [FILES...]   (default: README.md, docs/*.md, */README.md, results/*/README.md)
"""
import argparse
import glob
import json
import os
import pathlib
import re
import shlex
import subprocess
import sys

LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
CODE_PATH = re.compile(r"`([a-z_]+/[A-Za-z0-9_./+-]*[A-Za-z0-9_])`")
BLOCK = re.compile(r"```(?:sh|bash)\n(.*?)```", re.S)
SPLIT = re.compile(r"\s*(?:&&|\|\||;|\|)\s*")


class Checker:
    def __init__(self, root, build):
        self.root, self.build = root, build
        self.failures, self.checked = [], 0
        presets = json.loads((root / "CMakePresets.json").read_text())
        self.presets = {p["name"] for kind in ("configurePresets", "buildPresets", "testPresets", "workflowPresets")
                        for p in presets.get(kind, [])}
        cmake_text = "\n".join(p.read_text() for p in root.rglob("CMakeLists.txt") if "build" not in p.parts)
        self.targets = set(re.findall(r"add_executable\(\s*([A-Za-z0-9_.+-]+)", cmake_text))
        self.help_cache = {}

    def fail(self, where, message):
        self.failures.append(f"{where}: {message}")

    def links(self, path, text):
        for target in LINK.findall(text):
            if re.match(r"[a-z]+:", target) or target.startswith("#") or "::" in target:
                continue
            self.checked += 1
            if not (path.parent / target.split("#")[0]).exists():
                self.fail(os.path.relpath(path, self.root), f"link to {target}, which does not exist")

    def code_paths(self, path, text):
        prose = BLOCK.sub("", text)
        top = {p.name for p in self.root.iterdir() if p.is_dir() and p.name not in ("build", "out", "Testing")}
        for target in CODE_PATH.findall(prose):
            first = target.split("/")[0]
            if first not in top or "..." in target or "<" in target:
                continue
            self.checked += 1
            if not (self.root / target).exists() and not glob.glob(str(self.root / target)):
                self.fail(os.path.relpath(path, self.root), f"`{target}` does not exist")

    def help_text(self, exe, sub):
        key = (exe, sub)
        if key not in self.help_cache:
            text, status = "", 1
            for args in ([sub, "--help"] if sub else None, ["--help"]):
                if args is None:
                    continue
                r = subprocess.run([str(exe), *args], capture_output=True, text=True, timeout=60)
                if r.returncode == 0:
                    text, status = r.stdout + r.stderr, 0
                    break
            self.help_cache[key] = (text, status)
        return self.help_cache[key]

    def program(self, where, words):
        i = next(i for i, w in enumerate(words) if "/build/" in "/" + w and w.startswith(("./build/", "build/")))
        path, args = words[i], words[i + 1:]
        name = pathlib.PurePath(path).name
        parts = pathlib.PurePath(path.removeprefix("./")).parts  # build, <preset dir>, ..., program
        built = self.root / pathlib.PurePath(*parts) if pathlib.PurePath(*parts[:2]) == self.build else None
        if built is None or not built.is_file():
            if name not in self.targets:
                self.fail(where, f"{path}: no add_executable({name}) in the project")
            return
        sub = args[0] if args and not args[0].startswith("-") and "/" not in args[0] and "." not in args[0] else None
        text, status = self.help_text(built, sub)
        if status != 0:
            self.fail(where, f"{path} {sub or ''} --help exits non-zero")
            return
        for flag in (a.split("=")[0] for a in args if a.startswith("--")):
            if not re.search(re.escape(flag) + r"(?![a-z0-9_-])", text):
                self.fail(where, f"{path}: {flag} is not in its --help")

    def cmake(self, where, words):
        for i, w in enumerate(words):
            if w == "--preset" and i + 1 < len(words) and words[i + 1] not in self.presets:
                self.fail(where, f"preset {words[i + 1]} is not in CMakePresets.json")
        if words[0] == "ctest":
            for opt in ("-R", "-L"):
                if opt in words:
                    pattern = words[words.index(opt) + 1]
                    r = subprocess.run(["ctest", "--test-dir", str(self.root / self.build), "-N", opt, pattern],
                                       capture_output=True, text=True)
                    if not re.search(r"Total Tests: [1-9]", r.stdout):
                        self.fail(where, f"ctest {opt} {pattern} selects no test")

    def command(self, where, line):
        try:
            words = shlex.split(line, comments=True)
        except ValueError:
            self.fail(where, f"cannot parse: {line}")
            return
        while words and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[0]):
            words.pop(0)
        if not words or words[0] in ("export", "mkdir", "cp", "gunzip", "cd", "echo"):
            return
        self.checked += 1
        if words[0] in ("cmake", "ctest"):
            self.cmake(where, words)
        elif any(w.startswith(("./build/", "build/")) for w in words):
            self.program(where, words)
        elif words[0] in ("python3", "sh", "bash") or words[0].endswith((".sh", ".py")) or words[0].startswith("./"):
            script = next((w for w in words if w.endswith((".sh", ".py"))), None)
            if script and not (self.root / script).exists():
                self.fail(where, f"{script} does not exist")

    def page(self, path):
        text = path.read_text(encoding="utf-8")
        self.links(path, text)
        self.code_paths(path, text)
        for block in BLOCK.findall(text):
            joined = re.sub(r"\\\n", " ", block)
            for number, line in enumerate(joined.splitlines(), 1):
                for part in SPLIT.split(line.split(" #")[0]):
                    if part.strip():
                        self.command(f"{os.path.relpath(path, self.root)} ({part.strip()[:60]})", part.strip())


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", default=".", help="repository root [default .]")
    parser.add_argument("--build", default="build/release", help="build directory, relative to the root")
    parser.add_argument("files", nargs="*")
    args = parser.parse_args()
    root = pathlib.Path(args.root).resolve()
    files = args.files or ["README.md", *sorted(glob.glob("docs/*.md", root_dir=root)),
                           *sorted(glob.glob("*/README.md", root_dir=root)),
                           *sorted(glob.glob("results/*/README.md", root_dir=root))]
    checker = Checker(root, pathlib.Path(os.path.relpath(pathlib.Path(args.build).resolve(), root)))
    for f in files:
        checker.page((root / f).resolve())
    for failure in checker.failures:
        print("FAIL:", failure)
    if checker.failures:
        return 1
    print(f"PASS: {checker.checked} links and commands in {len(files)} pages")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Fails when a file in firmware/ includes a folder above its own layer.

The layers are the table in ARCHITECTURE.md ("| `folder/` | what | may
include |"): a file in firmware/FOLDER/ may include its own folder and the
folders its row names, nothing else. Also: an element kind (elements/KIND/)
includes no other kind, and firmware/ never includes tools/ or tests/.

  include_layers.py [ROOT]     check ROOT (default: this checkout)
  include_layers.py --self-test  show that a climbing include is caught
"""
import os
import re
import sys
import tempfile

ROW = re.compile(r"^\|\s*`([a-z_]+)/`\s*\|[^|]*\|([^|]*)\|\s*$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def read_layers(root):
    path = os.path.join(root, "ARCHITECTURE.md")
    layers = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = ROW.match(line.strip())
            if m:
                layers[m.group(1)] = set(re.findall(r"`([a-z_]+)`", m.group(2)))
    if not layers:
        sys.exit(f"{path}: no layer table (rows like | `core/` | what | `gl`, `core` |)")
    for folder, allowed in layers.items():
        unknown = allowed - layers.keys()
        if unknown:
            sys.exit(f"{path}: `{folder}/` may include {sorted(unknown)}, which the table does not list")
    return layers


def violations(root):
    layers = read_layers(root)
    firmware = os.path.join(root, "firmware")
    top_dirs = {d for d in os.listdir(root) if os.path.isdir(os.path.join(root, d))}
    found = []
    for dirpath, _, files in os.walk(firmware):
        for name in sorted(files):
            if not name.endswith((".h", ".cpp")):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, firmware).split(os.sep)
            folder = rel[0]
            if folder not in layers:
                found.append(f"firmware/{'/'.join(rel)}: firmware/{folder}/ has no row in "
                             "ARCHITECTURE.md's layer table (add one: what it may include)")
                continue
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            for target in INCLUDE.findall(text):
                parts = target.split("/")
                if len(parts) < 2:
                    continue  # generated headers (embedded_*.h) and same-folder includes
                dest = parts[0]
                where = f"firmware/{'/'.join(rel)}: #include \"{target}\""
                if dest in ("tools", "tests") or (dest in top_dirs and dest != "firmware"):
                    found.append(f"{where}: the runtime never includes {dest}/")
                elif dest not in layers:
                    continue  # a system or library header with a slash (toml++/toml.h)
                elif dest == folder:
                    if folder == "elements" and len(rel) > 2 and len(parts) > 2 and parts[1] != rel[1]:
                        found.append(f"{where}: the kind elements/{rel[1]}/ includes the kind "
                                     f"elements/{parts[1]}/ (only elements/element_kinds.cpp names kinds)")
                elif dest not in layers[folder]:
                    found.append(f"{where}: {folder}/ may include only "
                                 f"{', '.join(sorted(layers[folder])) or 'nothing'} (ARCHITECTURE.md): "
                                 f"{dest}/ is not below it")
    return found


def self_test():
    table = ("| folder | what | may include |\n|---|---|---|\n"
             "| `core/` | x | |\n| `wind/` | x | `core` |\n| `scene/` | x | `core`, `wind` |\n"
             "| `elements/` | x | `core`, `scene` |\n")
    cases = {
        "clean": ({"wind/wind.cpp": '#include "core/fixed.h"\n#include "embedded_noise.h"\n',
                   "scene/scene.cpp": '#include "wind/wind.h"\n#include <toml++/toml.h>\n',
                   "elements/kinds.cpp": '#include "elements/candle/candle.h"\n',
                   "elements/candle/candle.cpp": '#include "elements/candle/rig.h"\n'}, None),
        "climb": ({"wind/wind.cpp": '#include "scene/element.h"\n'},
                  'wind/ may include only core (ARCHITECTURE.md): scene/ is not below it'),
        "kind": ({"elements/candle/candle.cpp": '#include "elements/eigenflame/walker.h"\n'},
                 "the kind elements/candle/ includes the kind elements/eigenflame/"),
        "tools": ({"core/log.cpp": '#include "tools/model/pca.h"\n'}, "the runtime never includes tools/"),
        "unlisted": ({"story/plan.cpp": '#include "core/log.h"\n'}, "firmware/story/ has no row"),
    }
    for name, (files, expected) in cases.items():
        with tempfile.TemporaryDirectory() as root:
            with open(os.path.join(root, "ARCHITECTURE.md"), "w") as f:
                f.write(table)
            os.makedirs(os.path.join(root, "tools"))
            for rel, text in files.items():
                path = os.path.join(root, "firmware", rel)
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "w") as f:
                    f.write(text)
            found = violations(root)
            if expected is None and found:
                sys.exit(f"self-test {name}: a clean tree was refused: {found}")
            if expected is not None and not any(expected in v for v in found):
                sys.exit(f"self-test {name}: expected a violation saying {expected!r}, got {found}")
            print(f"self-test {name}: {'accepted' if expected is None else found[0]}")
    print("self-test: every climbing include was caught")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    found = violations(os.path.abspath(root))
    for v in found:
        print(v)
    if found:
        sys.exit(f"{len(found)} include(s) climb a layer (ARCHITECTURE.md)")
    print("every include in firmware/ goes down a layer (ARCHITECTURE.md)")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""candela-tool's option parsing against hostile values (issue 34):
tests/fuzz/tool_options.py BUILD_DIR [SECONDS] [SEED]

Every subcommand (but the studio window) is read from its own --help; each
option is given each hostile value of its type (NaN, infinities, signs,
overflow, hex, trailing text, empty, huge; for paths: /dev/zero, a FIFO, a
folder, a missing file, a 5000-character name), the rest left alone, with
inputs that do not exist; then random mixes of options and values until
SECONDS (default 30) are spent. Outputs go into a scratch folder. Each run
must end within 10 s (no hang), by exit status 0-3 (never a signal or a
sanitizer report), and when it fails say why on stderr as "candela-tool
NAME: ...". A failing run is printed as a command line to repeat it."""
import os, random, re, shlex, shutil, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from programs import program  # noqa: E402

BUILD = os.path.abspath(sys.argv[1])
BUDGET = float(sys.argv[2]) if len(sys.argv) > 2 else 30
rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
TOOL = program(os.path.join(BUILD, "tools", "candela-tool", "candela-tool"))
WORK = tempfile.mkdtemp(prefix="candela-tool-options-")
os.mkfifo(os.path.join(WORK, "fifo"))
os.mkdir(os.path.join(WORK, "folder"))

# Each option gets each of these in the sweep; the mixes draw from them too,
# and from the rarer ones below.
NUMBERS = ["nan", "inf", "-1", "0", "1e308", "5x"]
INPUTS = ["/dev/zero", os.path.join(WORK, "fifo"), os.path.join(WORK, "folder"), ""]
OUTPUTS = ["", "out.avi", "fifo"]
RARE = ["-inf", "1e-320", "99999999999999999999", "0x10", "", " 5", "x" * 5000,
        os.path.join(WORK, "missing.toml"), "deep/er/x.png", "folder"]


def options_of(sub):
    """(name, kind) for each option of `candela-tool SUB --help`: kind is
    "flag", "number" or "text"; and the positionals' names."""
    h = subprocess.run([*TOOL, sub, "--help"], capture_output=True, text=True, timeout=20).stdout
    opts, positionals, section = [], [], ""
    for line in h.splitlines():
        if line.endswith(":") and not line.startswith(" "):
            section = line
            continue
        m = re.match(r"^  (?:-\w,)?(--[\w-]+)(?: (\w+))?", line)
        if section.startswith("Options") and m and m.group(1) not in ("--help", "--version"):
            t = m.group(2) or ""
            opts.append((m.group(1), "number" if t in ("INT", "FLOAT", "UINT") else
                         "text" if t else "flag"))
        p = re.match(r"^  ([A-Z][A-Z_]*) ", line)
        if section.startswith("Positionals") and p:
            positionals.append(p.group(1))
    return opts, positionals


def is_output(name):
    return any(w in name for w in ("out", "save", "report", "plot", "csv", "json", "write"))


failures = []
runs = 0


def run(sub, args):
    global runs
    runs += 1
    cmd = [*TOOL, sub, *args]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=10, cwd=WORK,
                           stdin=subprocess.DEVNULL, errors="replace")
    except subprocess.TimeoutExpired:
        failures.append(("no end within 10 s", cmd))
        return
    err = p.stderr
    why = None
    if p.returncode < 0 or p.returncode > 3:
        why = "exit status %d" % p.returncode
    elif "Sanitizer" in err or "runtime error:" in err:
        why = "a sanitizer report"
    elif p.returncode != 0 and not re.search(r"^candela-tool( \w[\w-]*)?: ", err, re.M):
        why = "failed without a 'candela-tool NAME: ...' message"
    if why:
        failures.append((why + ": " + err.strip()[-300:], cmd))


subs = []
h = subprocess.run([*TOOL, "--help"], capture_output=True, text=True, timeout=20).stdout
in_subs = False
for line in h.splitlines():
    if line.startswith("Subcommands:"):
        in_subs = True
        continue
    m = re.match(r"^  ([\w-]+)", line)
    if in_subs and m and m.group(1) != "studio":  # the studio opens a window
        subs.append(m.group(1))
start = time.monotonic()
table = {s: options_of(s) for s in subs}
# Inputs that do not exist, so an accepted set of options fails fast.
def positionals(ps):
    return [os.path.join(WORK, "missing-" + p.lower()) for p in ps]

for sub, (opts, ps) in table.items():
    for name, kind in opts:
        values = ([None] if kind == "flag" else NUMBERS if kind == "number"
                  else OUTPUTS if is_output(name) else INPUTS)
        for v in values:
            run(sub, positionals(ps) + ([name] if v is None else [name, v]))
# Random mixes until the budget is spent.
while time.monotonic() - start < BUDGET:
    sub = rng.choice(subs)
    opts, ps = table[sub]
    args = positionals(ps) if rng.random() < 0.8 else [rng.choice(INPUTS)]
    for _ in range(rng.randint(1, 4)):
        if not opts:
            break
        name, kind = rng.choice(opts)
        if kind == "flag":
            args.append(name)
        else:
            pool = NUMBERS if kind == "number" else OUTPUTS if is_output(name) else INPUTS
            if not is_output(name):
                pool = pool + RARE
            args += [name, rng.choice(pool + ["1", "0.5", "8"])]
    run(sub, args)
shutil.rmtree(WORK, ignore_errors=True)
print("tool_options: %d runs of %d subcommands in %.0f s, %d failures"
      % (runs, len(subs), time.monotonic() - start, len(failures)))
for why, cmd in failures[:20]:
    print("FAIL %s\n     %s" % (why, shlex.join(cmd)))
sys.exit(1 if failures else 0)

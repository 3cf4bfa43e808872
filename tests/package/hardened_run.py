#!/usr/bin/python3
"""candela renders under the kiosk unit's sandbox, applied by hand.

hardened_run.py CANDELA UNIT SCRATCH [-- CANDELA-ARGS...]

With CANDELA-ARGS (e.g. `-- --display drm --test-pattern --frames 60` on the
virtual board) it only runs candela so under the sandbox, passes its output
and exit status through, and skips the frame comparison and probes.

No systemd runs as PID 1 on the build machines (so no `systemd-run -p ...`);
this applies the unit's main settings the way systemd does and checks that
`candela --display headless` renders frames identical to an unconfined run:
  User= (nobody here), NoNewPrivileges=, CapabilityBoundingSet= (empty),
  SystemCallFilter=@system-service with SystemCallErrorNumber=EPERM and
  SystemCallArchitectures=native, RestrictAddressFamilies=AF_UNIX AF_NETLINK
  (seccomp, libseccomp's python3-seccomp; the syscall list is expanded from
  this systemd's own `systemd-analyze syscall-filter`), ProtectSystem=strict,
  ProtectHome=, PrivateTmp=, ProtectKernelTunables= (a private mount
  namespace, everything read-only but the output and cache folders), UMask=,
  MemoryMax= and DevicePolicy=closed + DeviceAllow= (cgroup v1 memory and
  devices controllers, as systemd uses them on a v1 host). The values are read
  from UNIT. Probes in the same sandbox show it is real: writing /etc fails,
  an AF_INET socket is refused, an AF_UNIX one is not.
Exits 77 (skipped) without root, python3-seccomp or cgroup v1 controllers.
"""
import ctypes
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from programs import program  # noqa: E402

SKIP = 77
NOBODY = 65534


def unit_values(path):
    vals = {}
    for line in open(path):
        m = re.match(r"^([A-Za-z]+)=(.*)$", line.strip())
        if m:
            vals.setdefault(m.group(1), []).append(m.group(2))
    return vals


def syscall_groups():
    out = subprocess.run(["systemd-analyze", "syscall-filter"], capture_output=True, text=True,
                         check=True).stdout
    groups, cur = {}, None
    for line in out.splitlines():
        if line.startswith("@"):
            cur = groups.setdefault(line.strip(), [])
        elif cur is not None and line.strip() and not line.strip().startswith("#"):
            cur.append(line.strip())
    return groups


def expand(name, groups, seen=None):
    seen = set() if seen is None else seen
    out = set()
    for item in groups.get(name, []):
        if item.startswith("@"):
            if item not in seen:
                seen.add(item)
                out |= expand(item, groups, seen)
        else:
            out.add(item)
    return out


def inside(argv):
    """In the private mount namespace, as root: mounts, cgroups, then drop and exec."""
    unit, outdir, cg_dirs = argv[0], argv[1], argv[2].split(",")
    cmd = argv[3:]
    v = unit_values(unit)
    sh = lambda *c: subprocess.run(list(c), check=True)
    for cg in cg_dirs:  # MemoryMax=, DevicePolicy=: this process and what it execs
        with open(os.path.join(cg, "tasks"), "w") as f:
            f.write(str(os.getpid()))
    # ProtectSystem=strict: every mount read-only (ProtectKernelTunables: /sys, /proc/sys too).
    mounts = [l.split()[4] for l in open("/proc/self/mountinfo")]
    for m in mounts:
        if m.startswith(("/proc", "/dev")) and m != "/proc/sys":
            continue
        subprocess.run(["mount", "-o", "remount,bind,ro", m], stderr=subprocess.DEVNULL)
    sh("mount", "--bind", "/proc/sys", "/proc/sys")
    sh("mount", "-o", "remount,bind,ro", "/proc/sys")
    sh("mount", "-t", "tmpfs", "-o", "mode=1777", "tmpfs", "/tmp")  # PrivateTmp=
    for home in ["/home", "/root", "/run/user"]:  # ProtectHome=yes
        if os.path.isdir(home):
            sh("mount", "-t", "tmpfs", "-o", "mode=0", "tmpfs", home)
    sh("mount", "--bind", outdir, outdir)  # the one writable place (CacheDirectory=, output)
    sh("mount", "-o", "remount,bind,rw", outdir)  # a bind copies the source's read-only flag

    libc = ctypes.CDLL(None, use_errno=True)
    PR_CAPBSET_DROP = 24
    cap = 0
    while libc.prctl(PR_CAPBSET_DROP, cap, 0, 0, 0) == 0:  # CapabilityBoundingSet= (empty)
        cap += 1
    os.setgroups([])
    os.setgid(NOBODY)
    os.setuid(NOBODY)  # User=: no capabilities left after this
    os.umask(int(v["UMask"][0], 8))

    import seccomp  # Debian: python3-seccomp
    errno_eperm = 1
    f = seccomp.SyscallFilter(defaction=seccomp.ERRNO(errno_eperm))  # SystemCallErrorNumber=EPERM
    groups = syscall_groups()
    allowed = set()
    for spec in v["SystemCallFilter"]:
        for item in spec.split():
            allowed |= expand(item, groups) if item.startswith("@") else {item}
    families = {"AF_UNIX": 1, "AF_NETLINK": 16}
    fams = [families[a] for a in v["RestrictAddressFamilies"][0].split()]
    allowed.discard("socket")
    for name in sorted(allowed):
        try:
            f.add_rule(seccomp.ALLOW, name)
        except (RuntimeError, ValueError, OSError):
            pass  # not a syscall of this architecture
    for fam in fams:
        f.add_rule(seccomp.ALLOW, "socket", seccomp.Arg(0, seccomp.EQ, fam))
    f.load()  # libseccomp sets NoNewPrivileges first
    os.execv(cmd[0], cmd)


def main():
    if sys.argv[1] == "--inside":
        return inside(sys.argv[2:])
    candela, unit, scratch = [os.path.abspath(a) for a in sys.argv[1:4]]
    candela = program(candela)  # the command: an emulator first in a cross build
    extra = sys.argv[5:] if len(sys.argv) > 4 and sys.argv[4] == "--" else None
    if scratch.startswith(("/tmp/", "/home/", "/root/")):
        sys.exit("hardened_run: SCRATCH must not be under /tmp, /home or /root (the sandbox hides them)")
    if os.geteuid() != 0:
        print("skipped: needs root (mount namespace, cgroups)")
        return SKIP
    try:
        import seccomp  # noqa: F401
    except ImportError:
        print("skipped: no python3-seccomp (board/install-deps.sh)")
        return SKIP
    cgroot = "/sys/fs/cgroup"
    if not (os.path.isdir(cgroot + "/memory") and os.path.isdir(cgroot + "/devices")):
        print("skipped: no cgroup v1 memory/devices controllers here")
        return SKIP
    v = unit_values(unit)
    shutil.rmtree(scratch, ignore_errors=True)
    out = os.path.join(scratch, "out")
    os.makedirs(os.path.join(out, "cache"))
    for d in [out, os.path.join(out, "cache")]:
        os.chown(d, NOBODY, NOBODY)

    # cgroups: MemoryMax=, DevicePolicy=closed + DeviceAllow=.
    name = "candela-hardened-%d" % os.getpid()
    mem, dev = os.path.join(cgroot, "memory", name), os.path.join(cgroot, "devices", name)
    os.mkdir(mem)
    os.mkdir(dev)
    try:
        size = v["MemoryMax"][0]
        mult = {"K": 1 << 10, "M": 1 << 20, "G": 1 << 30}[size[-1]]
        open(os.path.join(mem, "memory.limit_in_bytes"), "w").write(str(int(size[:-1]) * mult))
        open(os.path.join(dev, "devices.deny"), "w").write("a")
        majors = {}
        section = None
        for line in open("/proc/devices"):
            if line.startswith("Character"):
                section = "char"
            elif line.startswith("Block"):
                section = "block"
            elif line.strip() and section == "char":
                num, dname = line.split()
                majors.setdefault(dname, num)
        # What DevicePolicy=closed always keeps (systemd's list), then DeviceAllow=.
        rules = ["c 1:3 rwm", "c 1:5 rwm", "c 1:7 rwm", "c 1:8 rwm", "c 1:9 rwm", "c 5:0 rwm",
                 "c 5:2 rwm", "c 136:* rw"]
        for d in v["DeviceAllow"]:
            cls, acc = d.split()
            if cls.startswith("char-") and cls[5:] in majors:
                rules.append("c %s:* %s" % (majors[cls[5:]], acc))
        for r in rules:
            open(os.path.join(dev, "devices.allow"), "w").write(r)

        def sandboxed(cmd, **kw):
            env = {"PATH": "/usr/bin:/bin", "XDG_CACHE_HOME": os.path.join(out, "cache")}
            return subprocess.run(["unshare", "--mount", "--propagation", "private", sys.executable,
                                   os.path.abspath(__file__), "--inside", unit, out, mem + "," + dev] + cmd,
                                  env=env, capture_output=True, text=True, **kw)

        if extra is not None:
            r = sandboxed(candela + extra)
            sys.stdout.write(r.stdout)
            sys.stderr.write(r.stderr)
            print("hardened_run: candela exited %d" % r.returncode)
            return r.returncode
        args = ["--display", "headless", "--size", "320x180", "--frames", "30"]
        ref = os.path.join(scratch, "reference.y4m")
        r = subprocess.run(candela + args + ["--out", ref], capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit("unconfined candela failed: " + r.stderr)
        hard = os.path.join(out, "hardened.y4m")
        r = sandboxed(candela + args + ["--out", hard])
        print(r.stderr.strip()[-1500:])
        failures = []
        if r.returncode != 0:
            failures.append("candela under the sandbox exited %d" % r.returncode)
        elif open(hard, "rb").read() != open(ref, "rb").read():
            failures.append("frames under the sandbox differ from the unconfined run")
        else:
            print("hardened: 30 frames identical to the unconfined run (%d bytes)" % os.path.getsize(hard))
        peak = int(open(os.path.join(mem, "memory.max_usage_in_bytes")).read())
        print("cgroup peak memory %.1f MB (MemoryMax=%s)" % (peak / 2**20, size))
        if peak == 0:
            failures.append("candela did not run in the memory cgroup")
        # The sandbox is real: the same wrapper refuses what the unit forbids.
        r = sandboxed(["/bin/sh", "-c", "echo x > /etc/candela-probe"])
        if r.returncode == 0 or os.path.exists("/etc/candela-probe"):
            failures.append("the sandbox let a write to /etc through")
        probe = ("import socket\nsocket.socket(socket.AF_UNIX).close()\n"
                 "try:\n  socket.socket(socket.AF_INET)\nexcept PermissionError:\n  print('inet refused')\n")
        r = sandboxed(["/usr/bin/python3", "-c", probe])
        if r.returncode != 0 or "inet refused" not in r.stdout:
            failures.append("socket probe: rc %d %r %r" % (r.returncode, r.stdout, r.stderr[-300:]))
        # /dev/fuse is open to everyone by its mode, but not in the unit's device list.
        if os.path.exists("/dev/fuse"):
            r = sandboxed(["/bin/sh", "-c", "if (exec 3</dev/fuse) 2>/dev/null; then echo opened; else echo denied; fi"])
            if "denied" not in r.stdout:
                failures.append("the device policy let /dev/fuse be opened: %r %r" % (r.stdout, r.stderr[-300:]))
        for f in failures:
            print("FAIL:", f)
        return 1 if failures else 0
    finally:
        for cg in [mem, dev]:
            try:
                os.rmdir(cg)
            except OSError as e:
                print("warning: could not remove cgroup %s: %s" % (cg, e))


sys.exit(main())

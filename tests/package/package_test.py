#!/usr/bin/python3
"""The Debian packages, as a user gets them (cmake/Packaging.cmake).

package_test.py BUILD_DIR SOURCE_DIR SCRATCH

Runs cpack on the existing build tree (nothing is rebuilt), runs lintian on
each .deb (no errors), unpacks them into a scratch root (dpkg-deb -x: the
files as dpkg would put them) and checks what a kiosk needs: the files and
which package has them, the conffile list, the unit, the sysusers file, the
udev rule, Depends from dpkg-shlibdeps, and that the unpacked `candela
--check` accepts the installed scenes (built-in and installed model files)
through the installed conffile. The postinst runs against stand-ins for
the commands it calls (systemd-sysusers, adduser, deb-systemd-helper, ...),
so what it would do on a board is checked without touching this machine.
"""
import glob
import os
import re
import shutil
import subprocess
import sys

build, source, scratch = sys.argv[1:4]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)

# 1. cpack on the build tree.
out = os.path.join(scratch, "debs")
r = run(["cpack", "--config", os.path.join(build, "CPackConfig.cmake"), "-B", out])
if r.returncode != 0:
    sys.exit("cpack failed:\n" + r.stdout + r.stderr)
debs = {}
for d in glob.glob(os.path.join(out, "*.deb")):
    name = run(["dpkg-deb", "-f", d, "Package"]).stdout.strip()
    debs[name] = d
print("packages:", {k: os.path.basename(v) for k, v in debs.items()})
if set(debs) != {"candela", "candela-tool"}:
    sys.exit("expected the packages candela and candela-tool, got %s" % sorted(debs))

# 2. lintian: no errors (warnings are printed, not fatal).
for name, d in debs.items():
    r = run(["lintian", "--fail-on", "error", "--tag-display-limit", "0", d])
    tags = [l for l in r.stdout.splitlines() if re.match(r"^[EWIX]: ", l)]
    for l in tags:
        print("lintian:", l)
    errors = [l for l in tags if l.startswith("E: ")]
    check(not errors, "%s: lintian errors: %s" % (name, errors))
    check(r.returncode == 0 or errors, "%s: lintian failed (rc %d): %s" % (name, r.returncode, r.stderr[-400:]))

# 3. Unpack both into one scratch root, as dpkg would install them.
root = os.path.join(scratch, "root")
contents = {}
for name, d in debs.items():
    subprocess.run(["dpkg-deb", "-x", d, root], check=True)
    subprocess.run(["dpkg-deb", "-e", d, os.path.join(scratch, "control-" + name)], check=True)
    listing = run(["dpkg-deb", "-c", d]).stdout.splitlines()
    contents[name] = {l.split()[-1].lstrip(".") for l in listing if not l.startswith("d")}


def ctrl(name, f):
    p = os.path.join(scratch, "control-" + name, f)
    return open(p).read() if os.path.exists(p) else None


kiosk, tool = contents["candela"], contents["candela-tool"]
scenes = sorted(os.path.basename(p) for p in glob.glob(os.path.join(source, "firmware/scenes/*.toml")))
for f in ["/usr/bin/candela", "/usr/bin/candela-record", "/lib/systemd/system/candela.service",
          "/usr/lib/sysusers.d/candela.conf", "/lib/udev/rules.d/60-candela-gpio.rules",
          "/etc/candela/candela.toml", "/usr/share/candela/models/default.cmodel",
          "/usr/share/candela/models/fire.cmodel", "/usr/share/doc/candela/copyright",
          "/usr/share/doc/candela/changelog.gz"] + ["/usr/share/candela/scenes/" + s for s in scenes]:
    check(f in kiosk, "candela lacks " + f)
check("/usr/bin/candela-tool" in tool, "candela-tool lacks /usr/bin/candela-tool")
check("/usr/bin/candela-tool" not in kiosk, "the kiosk package carries candela-tool")
check(not (tool & kiosk), "files in both packages: %s" % sorted(tool & kiosk))

# The conffile list, and the maintainer scripts' modes.
check((ctrl("candela", "conffiles") or "").split() == ["/etc/candela/candela.toml"],
      "candela's conffiles are %r, expected only /etc/candela/candela.toml" % ctrl("candela", "conffiles"))
for s in ["postinst", "prerm", "postrm"]:
    p = os.path.join(scratch, "control-candela", s)
    check(os.path.exists(p) and os.stat(p).st_mode & 0o777 == 0o755, "candela's %s missing or not 0755" % s)

# Depends from dpkg-shlibdeps: the kiosk's libraries, none of the tools'.
dep_kiosk = run(["dpkg-deb", "-f", debs["candela"], "Depends"]).stdout
dep_tool = run(["dpkg-deb", "-f", debs["candela-tool"], "Depends"]).stdout
print("candela Depends:", dep_kiosk.strip())
print("candela-tool Depends:", dep_tool.strip())
for lib in ["libegl1", "libgles2", "libgbm1", "libdrm2", "libudev1", "libpng16-16", "libc6", "adduser", "init-system-helpers"]:
    check(re.search(r"\b%s\b" % re.escape(lib), dep_kiosk), "candela does not depend on " + lib)
for lib in ["libavformat", "libavcodec", "libfftw3", "libeigen"]:
    check(lib not in dep_kiosk, "the kiosk package depends on %s (a tool's library)" % lib)
check("libavformat" in dep_tool and "libfftw3" in dep_tool, "candela-tool lacks its libav/FFTW Depends")

# The unit is the repository's hardened one, and names what the package installs.
unit = open(os.path.join(root, "lib/systemd/system/candela.service")).read()
check(unit == open(os.path.join(source, "board/systemd/candela.service")).read(),
      "the packaged unit differs from board/systemd/candela.service")
m = re.search(r"^ExecStart=(\S+) --config (\S+)", unit, re.M)
check(m and m.group(1) in kiosk and m.group(2) in kiosk, "the unit's ExecStart names files the package lacks")
check(re.search(r"^User=candela$", unit, re.M) and re.search(r"^WantedBy=multi-user.target$", unit, re.M),
      "the unit does not run as candela at boot")

# sysusers: the user, and its groups.
sysusers = open(os.path.join(root, "usr/lib/sysusers.d/candela.conf")).read()
check(re.search(r"^u candela - .* /nonexistent /usr/sbin/nologin$", sysusers, re.M),
      "sysusers.d/candela.conf does not make a no-login system user candela")
for g in ["video", "render", "input", "gpio"]:
    check(re.search(r"^m candela %s$" % g, sysusers, re.M), "sysusers: candela is not put in " + g)
r = run(["systemd-sysusers", "--dry-run", "--root", os.path.join(scratch, "sysroot"),
         os.path.join(root, "usr/lib/sysusers.d/candela.conf")])
check(r.returncode == 0 and "candela" in r.stdout + r.stderr,
      "systemd-sysusers rejects candela.conf: " + r.stdout + r.stderr)
rules = open(os.path.join(root, "lib/udev/rules.d/60-candela-gpio.rules")).read()
check(re.search(r'KERNEL=="gpiochip\[0-9\]\*", GROUP="gpio", MODE="0660"', rules),
      "the udev rule does not give /dev/gpiochip* to the gpio group")

# 4. The unpacked candela: the installed conffile, scenes and models.
candela = os.path.join(root, "usr/bin/candela")
conf = os.path.join(root, "etc/candela/candela.toml")
# As installed the conffile names the built-in default scene by name (what
# MQTT's select offers and `state` reports; issue 34): it checks as it is.
r = run([candela, "--config", conf, "--check"])
check(r.returncode == 0 and "built-in default" in r.stdout,
      "installed candela --config of the installed conffile: rc %d %s%s" % (r.returncode, r.stdout, r.stderr))
text = open(conf).read()
check(re.search(r'^scene = "default"$', text, re.M)
      and re.search(r'^display = "drm"$', text, re.M), "the conffile does not name the default scene and drm")
# A scene file named by path instead: the installed one under the scratch root.
rooted = os.path.join(scratch, "candela.toml")
open(rooted, "w").write(text.replace('scene = "default"', 'scene = "%s/usr/share/candela/scenes/default.toml"' % root))
r = run([candela, "--config", rooted, "--check"])
check(r.returncode == 0 and "default.toml: OK" in r.stdout,
      "installed candela --check of the installed default scene: rc %d %s%s" % (r.returncode, r.stdout, r.stderr))
# A file that is not there: a clear error naming the file and key.
missing = os.path.join(scratch, "missing.toml")
open(missing, "w").write(text.replace('scene = "default"', 'scene = "/nonexistent/default.toml"'))
r = run([candela, "--config", missing, "--check"])
check(r.returncode == 2 and re.search(re.escape(missing) + r": scene: expected a readable regular file", r.stderr),
      "a conffile naming a missing scene: rc %d, %r" % (r.returncode, r.stderr))
for s in scenes:
    r = run([candela, "--check", "--scene", os.path.join(root, "usr/share/candela/scenes", s)])
    check(r.returncode == 0, "installed candela --check %s: %s" % (s, r.stderr.strip()[-300:]))
# The installed model files, named by path instead of builtin:.
fire = open(os.path.join(root, "usr/share/candela/scenes/eigen-fireplace.toml")).read()
check('"builtin:fire"' in fire, "eigen-fireplace.toml no longer uses builtin:fire")
by_path = os.path.join(scratch, "fire-by-path.toml")
open(by_path, "w").write(fire.replace('"builtin:fire"', '"%s/usr/share/candela/models/fire.cmodel"' % root))
r = run([candela, "--check", "--scene", by_path])
check(r.returncode == 0, "the installed fire.cmodel named by path: " + r.stderr.strip()[-300:])
candle = open(os.path.join(root, "usr/share/candela/scenes/eigen-candle.toml")).read()
by_path = os.path.join(scratch, "candle-by-path.toml")
open(by_path, "w").write(candle.replace('"builtin:candle"', '"%s/usr/share/candela/models/default.cmodel"' % root))
r = run([candela, "--check", "--scene", by_path])
check(r.returncode == 0, "the installed default.cmodel named by path: " + r.stderr.strip()[-300:])

# 5. postinst configure against stand-ins that log their arguments.
def postinst(groups, have_sysusers, member_of):
    stubs = os.path.join(scratch, "stubs")
    shutil.rmtree(stubs, ignore_errors=True)
    os.makedirs(stubs)
    log = os.path.join(scratch, "calls.log")
    open(log, "w").close()
    def stub(name, body="exit 0"):
        p = os.path.join(stubs, name)
        open(p, "w").write('#!/bin/sh\necho "%s $*" >>"%s"\n%s\n' % (name, log, body))
        os.chmod(p, 0o755)
    stub("getent", 'case " %s " in *" $2 "*) exit 0;; esac; exit 2'
         % " ".join(groups))
    stub("id", 'echo "%s"' % " ".join(["candela"] + member_of))
    for c in ["adduser", "addgroup", "udevadm", "systemctl", "deb-systemd-invoke"]:
        stub(c)
    stub("deb-systemd-helper", '[ "$1" = --quiet ] && [ "$2" = was-enabled ] && exit 0; exit 0')
    if have_sysusers:
        stub("systemd-sysusers")
    for tool_name in ["tr", "grep"]:
        os.symlink(shutil.which(tool_name), os.path.join(stubs, tool_name))
    r = run(["/bin/sh", os.path.join(scratch, "control-candela", "postinst"), "configure", ""],
            env={"PATH": stubs})
    return r.returncode, open(log).read().splitlines()


rc, calls = postinst(["video", "render", "input"], True, ["video"])
print("postinst (sysusers):", calls)
check(rc == 0, "postinst configure exited %d" % rc)
check("systemd-sysusers candela.conf" in calls, "postinst did not run systemd-sysusers candela.conf")
check("adduser --quiet candela render" in calls and "adduser --quiet candela input" in calls,
      "postinst did not add candela to the render and input groups")
check(not any("candela video" in c or "candela gpio" in c for c in calls if c.startswith("adduser")),
      "postinst added a group candela already has (video) or one that does not exist (gpio)")
check("deb-systemd-helper enable candela.service" in calls, "postinst did not enable candela.service")
if not os.path.isdir("/run/systemd/system"):
    check(not any(c.startswith(("systemctl", "deb-systemd-invoke")) for c in calls),
          "postinst called systemctl without a running systemd")
rc, calls = postinst(["video", "render", "input", "gpio"], False, [])
print("postinst (adduser):", calls)
check(rc == 0 and any(c.startswith("adduser --quiet --system --group") for c in calls)
      and not any(c.startswith("addgroup") for c in calls),
      "postinst without systemd-sysusers: no adduser --system (or an existing gpio group made again)")
check(all("adduser --quiet candela %s" % g in calls for g in ["video", "render", "input", "gpio"]),
      "postinst without systemd-sysusers did not add all four groups")

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("package: OK")

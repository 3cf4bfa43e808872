"""How a test script starts a program of the build it tests (candela,
candela-record, candela-tool): program(path) is the command to run it.

In an arm64 cross build (board/arm64/) the programs are arm64 and this machine
runs them through qemu-user without binfmt_misc: ctest sets CANDELA_EMULATOR
for every test (tests/CMakeLists.txt: CMAKE_CROSSCOMPILING_EMULATOR, e.g.
/usr/bin/qemu-aarch64-static), and program() puts it in front. In every other
build it is empty and the command is the program itself.

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))), "support"))
    from programs import program
    CANDELA = program(os.path.join(BUILD, "firmware", "candela"))
    subprocess.run([*CANDELA, "--check"], ...)
"""
import mmap
import os
import shlex

EMULATOR = shlex.split(os.environ.get("CANDELA_EMULATOR", ""))


def program(path):
    """The command (a list) that runs the build's program at path here."""
    return EMULATOR + [path]


def sanitized(path):
    """Whether the program at path was built with AddressSanitizer
    (CANDELA_SANITIZE): its memory figures are ASan's, not the program's
    (freed memory stays resident in its quarantine)."""
    with open(path, "rb") as f, mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as m:
        return m.find(b"__asan_init") >= 0

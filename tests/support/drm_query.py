"""For the virtual board's DRM tests: what the kernel shows on a DRM device,
read with ioctls (no libdrm binding needed: the first CRTC, its framebuffer
and mode), and candela started on it as a kiosk runs it."""
import ctypes
import fcntl
import struct

DRM_IOCTL_MODE_GETRESOURCES = 0xC04064A0  # _IOWR('d', 0xA0, struct drm_mode_card_res)
DRM_IOCTL_MODE_GETCRTC = 0xC06864A1  # _IOWR('d', 0xA1, struct drm_mode_crtc)


def first_crtc(fd):
    """The id of the device's first CRTC."""
    res = bytearray(64)
    fcntl.ioctl(fd, DRM_IOCTL_MODE_GETRESOURCES, res, True)
    n = struct.unpack_from("<I", res, 36)[0]
    ids = (ctypes.c_uint32 * max(n, 1))()
    res = bytearray(struct.pack("<QQQQIIII", 0, ctypes.addressof(ids), 0, 0, 0, n, 0, 0) + bytes(16))
    fcntl.ioctl(fd, DRM_IOCTL_MODE_GETRESOURCES, res, True)
    return ids[0]


def crtc_state(fd, crtc):
    """(framebuffer id, mode width, mode height) of the CRTC."""
    c = bytearray(104)
    struct.pack_into("<I", c, 12, crtc)
    fcntl.ioctl(fd, DRM_IOCTL_MODE_GETCRTC, c, True)
    fb = struct.unpack_from("<I", c, 16)[0]
    hdisplay = struct.unpack_from("<H", c, 36 + 4)[0]  # drm_mode_modeinfo.hdisplay
    vdisplay = struct.unpack_from("<H", c, 36 + 14)[0]
    return fb, hdisplay, vdisplay


class CandelaOnDrm:
    """candela on the DRM display as a kiosk runs it: an unprivileged user in
    the video (and render, where it exists) group, no capabilities; its output
    in log_path."""

    def __init__(self, candela, log_path, extra_env, args=("--test-pattern", "--size", "640x480")):
        import os
        import subprocess
        groups = "video,render" if subprocess.run(["getent", "group", "render"],
                                                  capture_output=True).returncode == 0 else "video"
        env = dict(os.environ, HOME="/tmp", XDG_CACHE_HOME="/tmp", **extra_env)
        self.log_path = log_path
        with open(log_path, "w") as log:
            self.proc = subprocess.Popen(["setpriv", "--reuid=65534", "--regid=65534",
                                          "--groups=" + groups, "--inh-caps=-all", candela,
                                          "--display", "drm", *args],
                                         stdout=log, stderr=subprocess.STDOUT, env=env)

    def log_text(self):
        return open(self.log_path).read()

    def alive(self):
        """True while it runs; raises with its log once it has exited."""
        if self.proc.poll() is not None:
            raise AssertionError("candela exited (%d):\n%s" % (self.proc.returncode, self.log_text()))
        return True

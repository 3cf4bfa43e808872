"""What the kernel shows on a DRM device, read with ioctls (for the virtual
board's tests: no libdrm binding needed): the first CRTC and its framebuffer
and mode."""
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


def start_candela_on_drm(candela, log_path, extra_env, args=("--test-pattern", "--size", "640x480")):
    """candela on the DRM display as a kiosk runs it: an unprivileged user in
    the video (and render, where it exists) group, no capabilities; output to
    log_path. Returns the process."""
    import os
    import subprocess
    groups = "video,render" if subprocess.run(["getent", "group", "render"],
                                              capture_output=True).returncode == 0 else "video"
    env = dict(os.environ, HOME="/tmp", XDG_CACHE_HOME="/tmp", **extra_env)
    with open(log_path, "w") as log:
        return subprocess.Popen(["setpriv", "--reuid=65534", "--regid=65534", "--groups=" + groups,
                                 "--inh-caps=-all", candela, "--display", "drm", *args],
                                stdout=log, stderr=subprocess.STDOUT, env=env)

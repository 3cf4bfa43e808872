#!/usr/bin/env python3
"""candela over MQTT against a real broker: tests/input/mqtt_cli.py CASE BUILD_DIR.

Each case starts its own mosquitto (Debian `mosquitto`) on a free loopback port
and waits on what it says and publishes (no sleeps as synchronisation: every
wait is for a message, a log line or an exit, with a deadline). The client is
paho-mqtt (Debian `python3-paho-mqtt`).

  commands      Home Assistant discovery for a volume number entity (the schema's
                required and used keys, the device, availability), a gust button, a
                screen switch, a brightness number and a scene select; retained
                "online" and state; set/volume, set/wind, set/gust change the state
                and the state topic reports it (set/screen, set/brightness, set/scene
                too); a bad volume or unknown scene is refused with the
                parser's message and changes nothing; SIGTERM: "offline", exit 0
  reconnect     the broker stopped: candela runs on (frames advance), logs the loss
                once; the broker started again: candela reconnects and republishes
                its availability and state
  absent        no broker at start: one log line, frames advance, and when a broker
                appears on the port candela connects to it (the backoff retries)
  password      a wrong password: reported once, clearly (not authorised, check
                username and password_file); the right one: connected
  silent        a port that accepts and never answers: given up after the keepalive,
                retried, logged once
  off           no [mqtt]: candela opens no TCP socket at all
  config        [mqtt] mistakes are refused by --check naming the key
  room          three displays at [0,0], [1,0], [2,0] in one [room] (and one without):
                a gust sent to the first through its control socket is published once,
                and started by the second and third in order, each at the origin's
                time + the plane-S delay for its position, within one frame (16.7 ms);
                the origin ignores its own, nobody re-publishes, the one without
                [room] hears nothing; a bad message is logged and dropped, a late one
                is started at once
  huge          a 32 MiB set/scene payload (issue 34: buffered whole before the 1 KiB
                limit, RSS +390 MB for 200 MB): candela connects with MQTT v5 and a
                Maximum Packet Size, so the broker drops it: no reply to it, candela's
                peak RSS grows by less than 8 MiB, and the next command is answered
  bench         (not run by ctest) the round trips on loopback: the broker's echo, and
                a set/brightness to candela's reply and to its state reporting it
"""
import json, os, queue, select, shutil, signal, socket, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from programs import EMULATOR, program, sanitized  # noqa: E402

import paho.mqtt.client as mqtt

CASE, BUILD = sys.argv[1], sys.argv[2]
CANDELA = program(os.path.join(BUILD, "firmware", "candela"))
WORK = tempfile.mkdtemp(prefix="candela-mqtt-")
PREFIX = "test/candela%d" % os.getpid()
failures = []
procs = []


def check(ok, what, detail=""):
    print(("ok   " if ok else "FAIL ") + what + ("" if ok else " " + str(detail)[-1500:]))
    if not ok:
        failures.append(what)
    return ok


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


class Broker:
    """mosquitto on 127.0.0.1:port; ready when it logs that it is running."""

    def __init__(self, port, passwords=None, tls=None):
        conf = os.path.join(WORK, "mosquitto-%d.conf" % port)
        with open(conf, "w") as f:
            f.write("listener %d 127.0.0.1\npersistence false\nlog_dest stderr\nlog_type all\n" % port)
            if tls:  # (certificate, key): the listener speaks TLS only
                f.write("certfile %s\nkeyfile %s\n" % tls)
            if passwords:
                pw = os.path.join(WORK, "passwd")
                open(pw, "w").close()
                for user, password in passwords.items():
                    subprocess.run(["mosquitto_passwd", "-b", pw, user, password], check=True)
                # Started as root, mosquitto reads it as the user "mosquitto".
                os.chmod(WORK, 0o755)
                os.chmod(pw, 0o644)
                f.write("allow_anonymous false\npassword_file %s\n" % pw)
            else:
                f.write("allow_anonymous true\n")
        self.log_path = os.path.join(WORK, "mosquitto-%d.log" % port)
        self.p = subprocess.Popen(["mosquitto", "-c", conf], stderr=subprocess.PIPE)
        procs.append(self.p)
        deadline = time.monotonic() + 20
        self.log = b""
        fd = self.p.stderr.fileno()
        while time.monotonic() < deadline and b" running" not in self.log:
            r, _, _ = select.select([fd], [], [], max(0, deadline - time.monotonic()))
            chunk = os.read(fd, 65536) if r else b""
            if not chunk:
                break
            self.log += chunk
        if b" running" not in self.log:
            raise RuntimeError("mosquitto did not start: " + self.log.decode(errors="replace"))
        # From here on its log goes on into the pipe; drain it so it never blocks.
        import threading
        threading.Thread(target=lambda: [None for _ in iter(lambda: os.read(fd, 65536), b"")],
                         daemon=True).start()

    def stop(self):
        self.p.terminate()
        self.p.wait(timeout=20)


class Client:
    """Subscribed to everything candela publishes; messages queue up in order."""

    def __init__(self, port, user=None, password=None, ca=None):
        self.q = queue.Queue()
        self.c = mqtt.Client(client_id="test-%d-%d" % (os.getpid(), port), clean_session=True)
        if ca:
            self.c.tls_set(ca_certs=ca)
        if user:
            self.c.username_pw_set(user, password)
        self.c.on_message = lambda c, u, m: self.q.put((m.topic, m.payload.decode(), m.retain))
        connected = queue.Queue()
        self.c.on_connect = lambda c, u, f, rc: connected.put(rc)
        self.c.connect("127.0.0.1", port)
        self.c.loop_start()
        check(connected.get(timeout=10) == 0, "the test client connects")
        got = queue.Queue()
        self.c.on_subscribe = lambda c, u, mid, q: got.put(mid)
        self.c.subscribe([(PREFIX + "/#", 1), ("homeassistant/#", 1)])
        got.get(timeout=10)

    def wait(self, topic, pred=lambda p: True, timeout=20):
        """The first message on `topic` whose payload satisfies pred, or None."""
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            try:
                t, p, r = self.q.get(timeout=left)
            except queue.Empty:
                return None
            if t == topic and pred(p):
                return p

    def send(self, command, payload):
        self.c.publish(PREFIX + "/set/" + command, payload, qos=1)

    def close(self):
        self.c.loop_stop()
        self.c.disconnect()


def write_config(port, extra=""):
    path = os.path.join(WORK, "candela.toml")
    with open(path, "w") as f:
        f.write('[mqtt]\nhost = "127.0.0.1"\nport = %d\nprefix = "%s"\nreconnect_max = 1\n%s'
                % (port, PREFIX, extra))
    return path


def start_candela(config, *extra):
    log = open(os.path.join(WORK, "candela.log"), "w")
    cmd = [*CANDELA, "--display", "headless", "--test-pattern", "--size", "64x48", "--realtime",
           "--log-level", "info", *extra]
    if config:
        cmd += ["--config", config]
    p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
    procs.append(p)
    return p


def candela_log():
    return open(os.path.join(WORK, "candela.log")).read()


def stop_candela(p):
    p.send_signal(signal.SIGTERM)
    return p.wait(timeout=30)


def ask(ctl, line, timeout=20):
    """One control-socket question (the socket appears after start-up: waited for)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            s.settimeout(5)
            s.connect(ctl)
            s.sendall((line + "\n").encode())
            data = b""
            while not data.endswith(b"\n"):
                chunk = s.recv(4096)
                if not chunk:
                    break
                data += chunk
            s.close()
            return data.decode().strip()
        except OSError:
            time.sleep(0.01)  # polling for the socket to appear, bounded by the deadline
    return ""


def frames_advance(ctl, frames, timeout=30):
    """The display keeps drawing: `frames` more frames within the timeout."""
    start = json.loads(ask(ctl, "state") or '{"frame": -1}')["frame"]
    deadline = time.monotonic() + timeout
    now = start
    while time.monotonic() < deadline and now < start + frames:
        now = json.loads(ask(ctl, "state") or '{"frame": -1}')["frame"]
    return start >= 0 and now >= start + frames


def case_commands():
    port = free_port()
    broker = Broker(port)
    client = Client(port)
    p = start_candela(write_config(port))
    # In the order candela publishes them on connecting.
    check(client.wait(PREFIX + "/availability", lambda x: x == "online") is not None, "online")
    node = PREFIX.replace("/", "_")
    disc = client.wait("homeassistant/number/%s/volume/config" % node)
    check(disc is not None, "Home Assistant discovery config for a volume number entity", candela_log())
    if disc:
        d = json.loads(disc)
        # Home Assistant's MQTT number: command_topic required; what we use of the rest.
        check(d.get("command_topic") == PREFIX + "/set/volume", "command_topic is set/volume", d)
        check(d.get("state_topic") == PREFIX + "/state", "state_topic is the state topic", d)
        check(d.get("min") == 0 and d.get("max") == 1 and 0 < d.get("step", 0) <= 0.1,
              "a 0..1 range with a fine step", d)
        check(d.get("mode") in ("auto", "box", "slider"), "a valid mode", d)
        check(d.get("value_template") == "{{ value_json.volume }}", "the volume read from the state JSON", d)
        check(isinstance(d.get("unique_id"), str) and d["unique_id"], "a unique_id", d)
        dev = d.get("device", {})
        check(isinstance(dev.get("identifiers"), list) and dev["identifiers"] and dev.get("name"),
              "a device with identifiers and a name", d)
        check(d.get("availability_topic") == PREFIX + "/availability"
              and d.get("payload_available") == "online" and d.get("payload_not_available") == "offline",
              "availability online/offline", d)
    gust = client.wait("homeassistant/button/%s/gust/config" % node)
    check(gust is not None, "and for a gust button", candela_log())
    if gust and disc:
        g = json.loads(gust)
        check(g.get("command_topic") == PREFIX + "/set/gust" and g.get("payload_press") == "front"
              and g.get("unique_id") and g.get("device") == json.loads(disc).get("device"),
              "the button presses set/gust front, on the same device", g)
    # The kiosk's entities (issue 16): screen switch, brightness number, scene select.
    sw = client.wait("homeassistant/switch/%s/screen/config" % node)
    check(sw is not None, "discovery for a screen switch", candela_log())
    if sw and disc:
        w = json.loads(sw)
        check(w.get("command_topic") == PREFIX + "/set/screen" and w.get("payload_on") == "on"
              and w.get("payload_off") == "off" and w.get("state_topic") == PREFIX + "/state"
              and w.get("value_template") == "{{ value_json.screen }}"
              and w.get("state_on") == "on" and w.get("state_off") == "off"
              and w.get("unique_id") and w.get("device") == json.loads(disc).get("device"),
              "the switch commands set/screen on|off and reads value_json.screen", w)
    br = client.wait("homeassistant/number/%s/brightness/config" % node)
    check(br is not None, "discovery for a brightness number", candela_log())
    if br:
        b = json.loads(br)
        check(b.get("command_topic") == PREFIX + "/set/brightness" and b.get("min") == 0
              and b.get("max") == 1 and b.get("value_template") == "{{ value_json.brightness }}"
              and b.get("unique_id"), "the number commands set/brightness 0..1", b)
    se = client.wait("homeassistant/select/%s/scene/config" % node)
    check(se is not None, "discovery for a scene select", candela_log())
    if se:
        o = json.loads(se)
        check(o.get("command_topic") == PREFIX + "/set/scene"
              and o.get("value_template") == "{{ value_json.scene }}"
              and "eigen-fireplace" in o.get("options", []) and "default" in o.get("options", [])
              and not [x for x in o.get("options", []) if "bench" in x] and o.get("unique_id"),
              "the select offers the built-in scenes (no benchmarks) and commands set/scene", o)
    st = client.wait(PREFIX + "/state")
    check(st is not None and abs(json.loads(st)["volume"] - 0.6) < 1e-3, "state: volume 0.6 at first", st)
    if st:
        j = json.loads(st)
        check(j.get("screen") == "on" and j.get("scene") == "test-pattern" and j.get("brightness") == 1
              and isinstance(j.get("fps"), (int, float)) and isinstance(j.get("errors"), int),
              "state: screen, scene, brightness, fps and errors", st)
    client.send("screen", "off")
    check(client.wait(PREFIX + "/reply") == "ok", "set/screen off answers ok")
    check(client.wait(PREFIX + "/state", lambda x: json.loads(x)["screen"] == "off") is not None,
          "the state reports the screen off")
    client.send("screen", "on")
    check(client.wait(PREFIX + "/reply") == "ok", "set/screen on answers ok")
    client.send("brightness", "0.5")
    check(client.wait(PREFIX + "/reply") == "ok", "set/brightness 0.5 answers ok")
    check(client.wait(PREFIX + "/state", lambda x: json.loads(x)["brightness"] == 0.5
                      and json.loads(x)["screen"] == "on") is not None,
          "the state reports brightness 0.5, screen on")
    client.send("scene", "default")
    check(client.wait(PREFIX + "/reply", timeout=60) == "ok", "set/scene default answers ok")
    check(client.wait(PREFIX + "/state", lambda x: json.loads(x)["scene"] == "default") is not None,
          "the state reports the scene")
    client.send("scene", "no-such")
    r = client.wait(PREFIX + "/reply")
    check(r is not None and r.startswith("error: scene: over MQTT expected one of the scenes offered (")
          and "eigen-fireplace" in r, "an unknown scene is refused, naming the scenes offered", r)
    # Issue 34: a network client names scenes, never files: no path is
    # opened, so no reply tells whether a file exists or quotes it.
    secret = os.path.join(WORK, "secret.toml")
    with open(secret, "w") as f:
        f.write("hunter2-is-the-password\n")
    for path in (secret, "/etc/passwd", "/nonexistent/x.toml", "../default"):
        client.send("scene", path)
        r = client.wait(PREFIX + "/reply")
        check(r is not None and r.startswith("error: scene: over MQTT expected one of the scenes offered")
              and "hunter2" not in r and "exist" not in r and "regular file" not in r,
              "set/scene %s is refused before any file is opened" % path, r)
    st = client.wait(PREFIX + "/state", lambda x: json.loads(x)["scene"] == "default")
    check(st is not None, "and the running scene stays", st)
    client.send("volume", "0.25")
    check(client.wait(PREFIX + "/reply") == "ok", "set/volume 0.25 answers ok")
    st = client.wait(PREFIX + "/state", lambda x: abs(json.loads(x)["volume"] - 0.25) < 1e-3)
    check(st is not None, "the state reports volume 0.25")
    client.send("volume", "2")
    r = client.wait(PREFIX + "/reply")
    check(r is not None and r.startswith("error: volume: expected one level in [0, 1]"),
          "set/volume 2 is refused with the parser's message", r)
    client.send("state", "")
    st = client.wait(PREFIX + "/reply")
    check(st is not None and abs(json.loads(st)["volume"] - 0.25) < 1e-3, "the refused volume changed nothing", st)
    client.send("wind", "0.5 0")
    check(client.wait(PREFIX + "/reply") == "ok", "set/wind answers ok")
    # At the origin, past plane S: attenuated (0.38 of 0.5 in the test pattern's wind).
    st = client.wait(PREFIX + "/state", lambda x: json.loads(x)["wind"]["x"] > 0.3)
    check(st is not None, "the state reports the steady wind from the left")
    client.send("gust", "right 3")
    check(client.wait(PREFIX + "/reply") == "ok", "set/gust answers ok")
    st = client.wait(PREFIX + "/state", lambda x: json.loads(x)["wind"]["x"] < 0)
    check(st is not None, "the gust from the right shows in the state's wind")
    # The round trip a home automation sees: command published -> reply received.
    trips = []
    for i in range(20):
        t0 = time.monotonic()
        client.send("volume", "0.%02d" % (30 + i))
        if client.wait(PREFIX + "/reply") != "ok":
            break
        trips.append((time.monotonic() - t0) * 1000)
    trips.sort()
    check(len(trips) == 20, "20 volume commands answered")
    if trips:
        print("     MQTT round trip on loopback: median %.2f ms, max %.2f ms" % (trips[len(trips) // 2], trips[-1]))
    client.send("dance", "now")
    r = client.wait(PREFIX + "/reply")
    check(r is not None and r.startswith("error: unknown command"), "an unknown command is refused", r)
    rc = stop_candela(p)
    check(client.wait(PREFIX + "/availability", lambda x: x == "offline") is not None, "offline on exit")
    check(rc == 0, "exit 0", candela_log())
    client.close()
    broker.stop()


def peak_rss_kib(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    return -1


def case_huge():
    port = free_port()
    broker = Broker(port)
    client = Client(port)
    p = start_candela(write_config(port))
    check(client.wait(PREFIX + "/state") is not None, "connected and reporting", candela_log())
    # Answered: the command path is warm before the peak is read.
    client.send("volume", "0.5")
    check(client.wait(PREFIX + "/reply") == "ok", "set/volume 0.5 answers ok")
    before = peak_rss_kib(p.pid)
    client.c.publish(PREFIX + "/set/scene", b"x" * (32 << 20), qos=1).wait_for_publish(60)
    client.send("volume", "0.25")
    r = client.wait(PREFIX + "/reply", timeout=60)
    check(r == "ok", "the command after it is answered, and first: the huge one got no reply "
          "(the broker dropped it)", r)
    after = peak_rss_kib(p.pid)
    if EMULATOR:
        # Under qemu-user the process's peak is the emulator's too (its code
        # cache grows as new code runs): the missing reply above is the proof.
        print("     peak RSS not compared under %s" % EMULATOR[0])
    elif sanitized(CANDELA[-1]):
        # ASan keeps freed memory resident (its quarantine): the state
        # reports' churn alone grew the peak by 16 MiB once. The normal
        # build compares it; here the missing reply is the proof.
        print("     peak RSS not compared under AddressSanitizer")
    else:
        check(before > 0 and after - before < 8 << 10,
              "candela's peak RSS grew by %d KiB (under 8 MiB; the payload is 32 MiB)"
              % (after - before))
    check("maximum packet size" not in candela_log(), "the packet size was set", candela_log())
    check(stop_candela(p) == 0, "exit 0", candela_log())
    client.close()
    broker.stop()


def case_reconnect():
    port = free_port()
    ctl = os.path.join(WORK, "ctl")
    broker = Broker(port)
    client = Client(port)
    p = start_candela(write_config(port), "--control", ctl)
    check(client.wait(PREFIX + "/availability", lambda x: x == "online") is not None, "online")
    client.close()
    broker.stop()
    check(frames_advance(ctl, 90), "the display runs on without the broker")
    broker = Broker(port)
    client = Client(port)  # a fresh broker holds nothing retained: what comes is republished
    check(client.wait(PREFIX + "/availability", lambda x: x == "online", timeout=30) is not None,
          "reconnected: online again", candela_log())
    check(client.wait(PREFIX + "/state", timeout=30) is not None, "the state republished")
    log = candela_log()
    check(log.count("with backoff") == 1,
          "the outage is logged once", log)
    check("connected to 127.0.0.1:%d again" % port in log, "the reconnection is logged", log)
    check(stop_candela(p) == 0, "exit 0")
    client.close()
    broker.stop()


def case_retained():
    """A retained command is delivered again at every connect: a setting
    (volume) is applied again, an event (gust) is refused, or each reconnect
    of the kiosk would blow a gust."""
    port = free_port()
    ctl = os.path.join(WORK, "ctl")
    broker = Broker(port)
    client = Client(port)
    for command, payload in (("gust", "left 2"), ("volume", "0.25")):
        client.c.publish(PREFIX + "/set/" + command, payload, qos=1, retain=True).wait_for_publish()
    p = start_candela(write_config(port), "--control", ctl)
    refused = client.wait(PREFIX + "/reply", lambda x: "retained" in x)
    check(refused is not None and refused.startswith("error: gust: a retained message is not acted on"),
          "the retained gust is refused, saying why", refused)
    check(client.wait(PREFIX + "/state", lambda x: json.loads(x).get("volume") == 0.25) is not None,
          "the retained volume is applied")
    check(frames_advance(ctl, 30), "the display runs on")
    state = json.loads(ask(ctl, "state") or "{}")
    check(state.get("events") == 0 and state.get("wind", {}).get("x") == 0.0,
          "no gust was blown", state)
    client.send("gust", "left 2")  # the same command, not retained: blown
    check(client.wait(PREFIX + "/reply", lambda x: x.startswith("ok")) is not None,
          "the same gust sent without retain is taken")
    check(stop_candela(p) == 0, "exit 0")
    client.close()
    broker.stop()


def self_signed(name):
    """A certificate for 127.0.0.1 that is its own CA, and its key (openssl)."""
    cert, key = os.path.join(WORK, name + ".pem"), os.path.join(WORK, name + ".key")
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "2",
                    "-subj", "/CN=127.0.0.1", "-addext", "subjectAltName=IP:127.0.0.1",
                    "-keyout", key, "-out", cert], check=True, capture_output=True)
    os.chmod(WORK, 0o755)  # mosquitto, started as root, reads them as the user "mosquitto"
    os.chmod(key, 0o644)
    return cert, key


def case_tls():
    """[mqtt] tls = true: the broker's certificate is checked (against
    ca_file) and its name; commands and state travel encrypted. A broker
    whose certificate the kiosk does not trust is refused, logged once, and
    the display runs on."""
    port = free_port()
    ctl = os.path.join(WORK, "ctl")
    cert, key = self_signed("broker")
    broker = Broker(port, tls=(cert, key))
    client = Client(port, ca=cert)
    config = write_config(port, 'tls = true\nca_file = "broker.pem"\n')
    p = start_candela(config, "--control", ctl)
    check(client.wait(PREFIX + "/availability", lambda x: x == "online") is not None,
          "online over TLS", candela_log())
    client.send("volume", "0.3")
    check(client.wait(PREFIX + "/reply", lambda x: x.startswith("ok")) is not None,
          "a command over TLS is answered")
    check(json.loads(ask(ctl, "state") or "{}").get("volume") == 0.3, "and carried out")
    check("(TLS)" in candela_log(), "the log says the broker is reached over TLS", candela_log())
    check(stop_candela(p) == 0, "exit 0")
    # Another CA: the broker's certificate is not trusted.
    self_signed("stranger")
    p = start_candela(write_config(port, 'tls = true\nca_file = "stranger.pem"\n'),
                      "--control", ctl)
    check(frames_advance(ctl, 120), "the display runs while the broker is not trusted")
    log = candela_log()
    check("connected to" not in log, "no connection to an untrusted broker", log)
    check(log.count("with backoff") == 1 and "certificate verify failed" in log
          and "check [mqtt] ca_file" in log, "the failure is logged once, saying why", log)
    check(stop_candela(p) == 0, "exit 0")
    client.close()
    broker.stop()


def case_absent():
    port = free_port()
    ctl = os.path.join(WORK, "ctl")
    p = start_candela(write_config(port), "--control", ctl)
    check(frames_advance(ctl, 180), "the display runs without a broker (3 s of frames)")
    log = candela_log()
    check(log.count("with backoff") == 1,
          "logged once, not at every retry", log)
    broker = Broker(port)
    client = Client(port)
    check(client.wait(PREFIX + "/availability", lambda x: x == "online", timeout=30) is not None,
          "a broker that appears is connected to", candela_log())
    check(stop_candela(p) == 0, "exit 0")
    client.close()
    broker.stop()


def case_password():
    port = free_port()
    broker = Broker(port, passwords={"kiosk": "right-password", "test": "test"})
    ctl = os.path.join(WORK, "ctl")
    pw = os.path.join(WORK, "mqtt.pass")
    with open(pw, "w") as f:
        f.write("wrong-password\n")
    os.chmod(pw, 0o600)
    p = start_candela(write_config(port, 'username = "kiosk"\npassword_file = "mqtt.pass"\n'),
                      "--control", ctl)
    check(frames_advance(ctl, 120), "the display runs while the login is refused")
    log = candela_log()
    check(log.count("refused the connection") == 1, "the refusal is logged once", log)
    check("not authorised" in log and "check [mqtt] username and password_file" in log,
          "and says what to check", log)
    check(stop_candela(p) == 0, "exit 0")
    with open(pw, "w") as f:
        f.write("right-password\n")
    client = Client(port, "test", "test")
    p = start_candela(os.path.join(WORK, "candela.toml"))
    check(client.wait(PREFIX + "/availability", lambda x: x == "online") is not None,
          "the right password connects", candela_log())
    check(stop_candela(p) == 0, "exit 0")
    client.close()
    broker.stop()


def case_silent():
    # Something on the port that accepts and never answers like a broker.
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(4)
    port = srv.getsockname()[1]
    ctl = os.path.join(WORK, "ctl")
    p = start_candela(write_config(port, "keepalive = 5\n"), "--control", ctl)
    srv.settimeout(20)
    first, _ = srv.accept()
    t0 = time.monotonic()
    check(frames_advance(ctl, 60), "the display runs while the port stays silent")
    try:
        second, _ = srv.accept()  # candela gave up on the first and tries again
        waited = time.monotonic() - t0
        check(4 <= waited <= 15, "gave up after the keepalive (5 s) and retried (%.1f s)" % waited)
        second.close()
    except socket.timeout:
        check(False, "candela never gave up on a silent port", candela_log())
    first.close()
    log = candela_log()
    check(log.count("with backoff") == 1, "logged once", log)
    check(stop_candela(p) == 0, "exit 0")
    srv.close()


def tcp_sockets(pid):
    inodes = set()
    for fd in os.listdir("/proc/%d/fd" % pid):
        try:
            link = os.readlink("/proc/%d/fd/%s" % (pid, fd))
        except OSError:
            continue
        if link.startswith("socket:["):
            inodes.add(link[8:-1])
    tcp = set()
    for table in ("tcp", "tcp6"):
        with open("/proc/%d/net/%s" % (pid, table)) as f:
            for row in f.readlines()[1:]:
                tcp.add(row.split()[9])
    return inodes & tcp


def case_off():
    ctl = os.path.join(WORK, "ctl")
    p = start_candela(None, "--control", ctl)
    check(frames_advance(ctl, 30), "candela runs")
    check(not tcp_sockets(p.pid), "no TCP socket without [mqtt]", tcp_sockets(p.pid))
    check("mqtt:" not in candela_log(), "and nothing about MQTT in the log", candela_log())
    check(stop_candela(p) == 0, "exit 0")


def case_config():
    pw = os.path.join(WORK, "p")
    open(pw, "w").write("secret\n")
    for body, key, what in [
        ('port = 1883\n', "mqtt.host", "missing"),
        ('host = "a b"\n', "mqtt.host", "host name"),
        ('host = "h"\nport = 0\n', "mqtt.port", "[1, 65535]"),
        ('host = "h"\nprefix = "a/+/b"\n', "mqtt.prefix", "no wildcards"),
        ('host = "h"\nprefix = "a//b"\n', "mqtt.prefix", "no empty level"),
        ('host = "h"\npassword_file = "p"\n', "mqtt.password_file", "without a username"),
        ('host = "h"\nusername = "u"\npassword_file = "nope"\n', "mqtt.password_file", ""),
        ('host = "h"\nreconnect_max = 0\n', "mqtt.reconnect_max", ""),
        ('host = "h"\ntls = "yes"\n', "mqtt.tls", ""),
        ('host = "h"\nca_file = "p"\n', "mqtt.ca_file", "without tls = true"),
        ('host = "h"\ntls = true\nca_file = "nope.pem"\n', "mqtt.ca_file", "readable regular file"),
        ('host = "h"\ntls = true\ncert_file = "p"\n', "mqtt.cert_file", "together"),
        # Issue 34: what only failed at the first connection.
        ('host = ":::"\n', "mqtt.host", "host name"),
        ('host = "broker..lan"\n', "mqtt.host", "host name"),
        ('host = "h"\ntls = true\nca_file = "p"\n', "mqtt.ca_file", "expected a PEM file"),
    ]:
        path = os.path.join(WORK, "bad.toml")
        open(path, "w").write("[mqtt]\n" + body)
        r = subprocess.run([*CANDELA, "--config", path, "--test-pattern", "--check"],
                           capture_output=True, text=True, timeout=60)
        check(r.returncode == 2 and key in r.stderr and what in r.stderr and path in r.stderr,
              "refused: %s" % body.strip().replace("\n", "; "), r.stderr)
    path = os.path.join(WORK, "good.toml")
    open(path, "w").write('[mqtt]\nhost = "broker.lan"\nusername = "u"\npassword_file = "p"\n')
    r = subprocess.run([*CANDELA, "--config", path, "--test-pattern", "--check"],
                       capture_output=True, text=True, timeout=60)
    check(r.returncode == 0, "a good [mqtt] passes --check", r.stderr)
    v6 = os.path.join(WORK, "v6.toml")
    open(v6, "w").write('[mqtt]\nhost = "::1"\n')
    r = subprocess.run([*CANDELA, "--config", v6, "--test-pattern", "--check"],
                       capture_output=True, text=True, timeout=60)
    check(r.returncode == 0, "an IPv6 address passes --check", r.stderr)
    os.chmod(pw, 0o644)
    r = subprocess.run([*CANDELA, "--config", path, "--test-pattern", "--check"],
                       capture_output=True, text=True, timeout=60)
    check("can be read by others (mode 644); chmod 600 it" in r.stderr,
          "a password file others can read is warned about", r.stderr)
    os.chmod(pw, 0o600)
    r = subprocess.run([*CANDELA, "--config", path, "--test-pattern", "--check"],
                       capture_output=True, text=True, timeout=60)
    check("can be read by others" not in r.stderr, "not when it is 0600", r.stderr)


def case_room():
    port = free_port()
    Broker(port)
    client = Client(port)
    room = PREFIX + "/room"
    names = ["a", "b", "c", "solo"]
    xs = {"a": 0.0, "b": 1.0, "c": 2.0}
    ps, ctl, logs = {}, {}, {}
    t_start = time.monotonic()
    for n in names:
        conf = os.path.join(WORK, n + ".toml")
        with open(conf, "w") as f:
            f.write('[mqtt]\nhost = "127.0.0.1"\nport = %d\nprefix = "%s/%s"\ndiscovery = false\n'
                    % (port, PREFIX, n))
            if n in xs:
                f.write('[room]\nposition = [%g, 0]\ntopic = "%s"\n' % (xs[n], room))
        ctl[n] = os.path.join(WORK, n + ".ctl")
        logs[n] = os.path.join(WORK, n + ".log")
        cmd = [*CANDELA, "--display", "headless", "--test-pattern", "--size", "64x48", "--realtime",
               "--log-level", "debug", "--config", conf, "--control", ctl[n]]
        ps[n] = subprocess.Popen(cmd, stdout=open(logs[n], "w"), stderr=subprocess.STDOUT)
        procs.append(ps[n])
    log = lambda n: open(logs[n]).read()
    # All four online, in whatever order they connect.
    waiting = {"%s/%s/availability" % (PREFIX, n): n for n in names}
    deadline = time.monotonic() + 20
    while waiting and time.monotonic() < deadline:
        try:
            t, p, _ = client.q.get(timeout=max(0.01, deadline - time.monotonic()))
        except queue.Empty:
            break
        if p == "online":
            waiting.pop(t, None)
    check(not waiting, "all four online", {n: log(n)[-500:] for n in waiting.values()})
    state = lambda n: json.loads(ask(ctl[n], "state") or "{}")
    check("room" not in state("solo"), "no [room]: no room in state")
    check(ask(ctl["a"], "gust left 2") == "ok", "a gust to a through its control socket")
    msg = client.wait(room + "/gust")
    check(msg is not None, "a publishes it on the room topic", log("a"))
    if msg is None:
        return
    g = json.loads(msg)
    check(g["origin"] == "candela-" + (PREFIX + "/a").replace("/", "_") and g["type"] == "gust"
          and abs(g["x"] - 2) < 1e-3 and g["z"] == 0 and g["position"] == [0, 0],
          "the message: origin, type, strength, position", g)
    # b and c start it when it reaches them: 1 m and 2 m downwind at the
    # scene's 1.5 m/s.
    applied = {}
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and len(applied) < 2:
        for n in ("b", "c"):
            if n not in applied:
                st = state(n)
                if st.get("room", {}).get("applied", 0) >= 1:
                    applied[n] = st["room"]
    check(len(applied) == 2, "b and c start the gust", {n: log(n)[-800:] for n in ("b", "c")})
    frame_ms = 1000.0 / 60
    for n in applied:
        r = applied[n]["last"]
        want = xs[n] / 1.5 * 1000
        got = (r["applied_ns"] - g["t_ns"]) / 1e6
        print("     %s at x=%g: due +%.1f ms after the origin, started at +%.1f ms (%+.1f ms); "
              "the message took %.2f ms from the origin's frame through the broker"
              % (n, xs[n], want, got, got - want, (r["received_ns"] - g["t_ns"]) / 1e6))
        check(r["origin_ns"] == g["t_ns"], n + ": the origin's time is carried", r)
        check(abs((r["due_ns"] - r["origin_ns"]) / 1e6 - want) < 0.5,
              n + ": due at the origin's time + the plane-S delay", r)
        # Within one frame of its time; later only where the frame loop
        # itself ran no frame between the gust's time and its start (a
        # loaded CI machine can hold a display's frame back by tens of ms):
        # the frame before it was still before its time.
        gap = (r["applied_ns"] - r["frame_before_ns"]) / 1e6
        check(0 < gap < 1000, n + ": the frame before its start is reported", r)
        held_by_loop = got - want > frame_ms and r["frame_before_ns"] < r["due_ns"]
        if held_by_loop:
            print("     %s: no frame between %.1f ms before its time and its start (%.1f ms apart)"
                  % (n, (r["due_ns"] - r["frame_before_ns"]) / 1e6, gap))
        check(abs(got - want) <= frame_ms or held_by_loop,
              n + ": started within one frame of its time, or on the first frame after it",
              (got - want, gap))
    if len(applied) == 2:
        check(applied["b"]["last"]["applied_ns"] < applied["c"]["last"]["applied_ns"],
              "the draught crosses the row in order: b before c")
    sa = state("a")["room"]
    check(sa["sent"] == 1 and sa["last_sent_ns"] == g["t_ns"] and sa["own"] == 1
          and sa["applied"] == 0, "a: sent once, its own echo ignored", sa)
    for n in ("b", "c"):
        r = state(n)["room"]
        check(r["sent"] == 0 and r["received"] == 1 and r["late"] == 0,
              n + ": received once, re-published nothing", r)
    check(client.wait(room + "/gust", timeout=0.3) is None, "no other message on the room topic")
    solo = state("solo")
    check("room" not in solo and solo["events"] == 0, "the display without [room] heard nothing",
          solo)
    # A bad message: logged and dropped, the display runs on.
    client.c.publish(room + "/gust", '{"v":1,"origin":"x"', qos=1)
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and state("b")["room"]["invalid"] < 1:
        pass
    check(state("b")["room"]["invalid"] == 1 and "room: dropped a message on %s/gust: expected JSON"
          % room in log("b"), "bad JSON: logged and dropped", log("b")[-600:])
    check(frames_advance(ctl["b"], 10), "b draws on")
    # A late one (sent 1 s ago from x=0: due at b 333 ms ago): started at once.
    late = dict(g, origin="test", seq=1, t_ns=time.time_ns() - 1_000_000_000)
    client.c.publish(room + "/gust", json.dumps(late), qos=1)
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and state("b")["room"]["applied"] < 2:
        pass
    r = state("b")["room"]
    check(r["late"] == 1 and r["applied"] == 2 and "came " in log("b")
          and "after its time (broker round trip); started at once" in log("b"),
          "a late gust: started at once, said at debug level", r)
    print("     whole case: %.1f s" % (time.monotonic() - t_start))
    for n in names:
        check(stop_candela(ps[n]) == 0, n + " exits 0")


def case_bench():
    """Not a test (ctest does not run it): the MQTT round trips on loopback.
    broker: a message published and received back by one client (QoS 0);
    command: set/brightness published until candela's reply "ok" arrives, and
    until its state topic reports the new value (its MQTT thread, the frame
    loop at 60 fps, and back)."""
    port = free_port()
    Broker(port)
    client = Client(port)

    def spread(xs):
        xs = sorted(xs)
        return xs[len(xs) // 2] * 1e3, xs[int(len(xs) * 0.95)] * 1e3

    broker = []
    for i in range(300):
        t = time.perf_counter()
        client.c.publish(PREFIX + "/echo", str(i), qos=0)
        if client.wait(PREFIX + "/echo", lambda x, i=i: x == str(i), timeout=5) is None:
            check(False, "the broker echoes message %d" % i)
            return
        broker.append(time.perf_counter() - t)
    p = start_candela(write_config(port))
    check(client.wait(PREFIX + "/availability", lambda x: x == "online") is not None, "candela online")
    reply, state = [], []
    for i in range(60):
        level = 0.3 + 0.01 * (i % 50)
        t = time.perf_counter()
        client.send("brightness", "%.2f" % level)
        ok = client.wait(PREFIX + "/reply", lambda x: x == "ok", timeout=10) is not None
        reply.append(time.perf_counter() - t)
        ok = ok and client.wait(PREFIX + "/state",
                                lambda x, level=level: abs(json.loads(x)["brightness"] - level) < 1e-6,
                                timeout=10) is not None
        state.append(time.perf_counter() - t)
        if not ok:
            check(False, "brightness %.2f answered and reported" % level)
            break
    b50, b95 = spread(broker)
    r50, r95 = spread(reply)
    s50, s95 = spread(state)
    print("mqtt round trip on loopback (ms): broker p50 %.2f p95 %.2f; "
          "candela reply p50 %.2f p95 %.2f (%.0fx the broker's); state p50 %.2f p95 %.2f"
          % (b50, b95, r50, r95, r50 / b50, s50, s95))
    check(stop_candela(p) == 0, "candela exits 0")


try:
    {"bench": case_bench, "room": case_room, "commands": case_commands, "reconnect": case_reconnect, "absent": case_absent,
     "password": case_password, "huge": case_huge, "off": case_off, "config": case_config,
     "silent": case_silent, "retained": case_retained, "tls": case_tls}[CASE]()
finally:
    for p in procs:
        if p.poll() is None:
            p.kill()
            p.wait()
    shutil.rmtree(WORK, ignore_errors=True)
sys.exit(1 if failures else 0)

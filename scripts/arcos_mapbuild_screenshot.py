#!/usr/bin/env python3
"""Builds a sonar map through ARCOS and photographs the window (docs/images/irgs-arcos-mapbuild.png).

Starts the virtual Pioneer (irgs-robot --protocol arcos) on a pty, connects the ground station
to it with protocol=arcos, runs map building to the end through --control-stdin and saves a
screenshot. Run under a display (xvfb-run) for a real window:

  xvfb-run -a -s "-screen 0 1600x1000x24" scripts/arcos_mapbuild_screenshot.py build OUT.png
"""
import os
import subprocess
import sys
import tempfile
import time

build, out = sys.argv[1], os.path.abspath(sys.argv[2])
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
res = os.path.join(root, "resources")
arena = os.path.join(res, "maps", "thesis_arena_250.json")
amigo = os.path.join(res, "robots", "pioneer_amigo.json")
work = tempfile.mkdtemp(prefix="irgs-arcos-shot-")
link = os.path.join(work, "robot")

robot = subprocess.Popen([os.path.join(build, "app/robot/irgs-robot"), "--protocol", "arcos",
                          "--map", arena, "--robot", amigo, "--link", link, "--baud", "115200",
                          "--seed", "3"], stdout=subprocess.PIPE, text=True)
print("robot:", robot.stdout.readline().strip())
gui = subprocess.Popen([os.path.join(build, "app/gui/irgs"), "--settings",
                        os.path.join(work, "settings.ini"), "--map", arena, "--robot", amigo,
                        "--window-size", "1400x880", "--connect",
                        "serial://" + link + "?baud=115200&protocol=arcos", "--control-stdin",
                        "--status-interval", "1"],
                       stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, bufsize=1)


def send(line):
    gui.stdin.write(line + "\n")
    gui.stdin.flush()


def field(line, key):
    for word in line.split():
        if word.startswith(key + "="):
            return word[len(key) + 1:]
    return None


started = False
deadline = time.time() + 600
try:
    for line in gui.stdout:
        if time.time() > deadline:
            sys.exit("timed out")
        if line.startswith("console "):
            print(line.strip())
            continue
        if not line.startswith("status"):
            continue
        if not started and field(line, "link") == "connected":
            send("mapbuild start")
            started = True
        elif started and field(line, "mb") in ("done", "failed", "aborted"):
            print("map building:", field(line, "mb"), "indices", field(line, "mb_indices"))
            time.sleep(1.0)
            send("screenshot " + out)
            time.sleep(2.0)
            send("quit")
            break
finally:
    gui.wait(timeout=60)
    robot.terminate()
print("wrote", out)

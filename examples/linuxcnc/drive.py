#!/usr/bin/python3
"""LinuxCNC's display program for test.sh: drives the simulated hexapod along a path and
records what the motion controller reports, sample by sample.

linuxcnc starts it as `drive.py -ini FILE`. The environment names the path file
(LINKAGE_PATH: one command per line, `mdi <G-code>` or `jog <velocity> <d0> … <d5>` for an
incremental move of the six joints together in joint mode), the output CSV (LINKAGE_OUT) and
the kinematics pin prefix (LINKAGE_KINS). Each sample holds the joint feedback, the Cartesian
feedback the module's kinematicsForward computed from it in the same servo cycle (task copies
both from one motion status), the commanded pose, the fwd-kins-fail pin, and for
linkagehexkins its proximity, failures (a count: a failed call between two samples leaves the
Cartesian feedback stale while fwd-kins-fail may already be clear again), last-failure and
certified pins.
"""
import os
import sys
import time

import hal
import linuxcnc

out = open(os.environ["LINKAGE_OUT"], "w")
log = open(os.environ["LINKAGE_OUT"] + ".log", "w")
sys.stdout = sys.stderr = log
kins = os.environ["LINKAGE_KINS"]
path = [l.split() for l in open(os.environ["LINKAGE_PATH"]) if l.strip() and not l.startswith("#")]

# hal.get_value needs a component of our own.
comp = hal.component("linkage-drive")
comp.ready()
s = linuxcnc.stat()
c = linuxcnc.command()
e = linuxcnc.error_channel()


def fail(why):
    print("drive.py: " + why, flush=True)
    out.write("# error: " + why + "\n")
    out.close()
    sys.exit(1)


def wait(pred, seconds, what):
    end = time.time() + seconds
    while time.time() < end:
        s.poll()
        if pred():
            return
        time.sleep(0.005)
    fail("timed out waiting for " + what)


def errors():
    msg = e.poll()
    if msg:
        print("linuxcnc error:", msg[1], flush=True)


out.write("step,t,j0,j1,j2,j3,j4,j5,x,y,z,a,b,c,cx,cy,cz,ca,cb,cc,fail,proximity,failures,last_failure,certified\n")
t0 = time.time()
has_proximity = any(p["NAME"] == kins + ".proximity" for p in hal.get_info_pins())


def sample(step):
    # One status copy: joints and pose as task copied them from the motion controller (a copy
    # torn across a servo cycle pairs them from adjacent cycles; the report recognises those).
    s.poll()
    j = s.joint_actual_position[:6]
    p = s.actual_position[:6]
    q = s.position[:6]
    f = int(bool(hal.get_value(kins + ".fwd-kins-fail")))
    # linkagehexkins' singularity proximity pin (genhexkins has none).
    prox = hal.get_value(kins + ".proximity") if has_proximity else float("nan")
    failures = hal.get_value(kins + ".failures") if has_proximity else 0
    last = hal.get_value(kins + ".last-failure") if has_proximity else 0
    certified = int(bool(hal.get_value(kins + ".certified"))) if has_proximity else 0
    out.write("%d,%.4f,%s,%s,%s,%d,%.6g,%d,%d,%d\n" % (step, time.time() - t0, ",".join("%.12g" % v for v in j),
              ",".join("%.12g" % v for v in p), ",".join("%.12g" % v for v in q), f, prox, failures, last, certified))


def run_until_done(step, done, seconds):
    start = time.time()
    while time.time() - start < seconds:
        sample(step)
        if time.time() - start > 0.05 and done():
            sample(step)
            return
        time.sleep(0.001)
    fail("step %d did not finish in %g s" % (step, seconds))


wait(lambda: True, 5, "status")
c.state(linuxcnc.STATE_ESTOP_RESET)
c.state(linuxcnc.STATE_ON)
wait(lambda: s.task_state == linuxcnc.STATE_ON, 10, "machine on")
c.mode(linuxcnc.MODE_MANUAL)
c.wait_complete()
c.home(-1)
wait(lambda: all(s.homed[:6]), 20, "homing")
sample(0)

for k, cmd in enumerate(path, start=1):
    errors()
    if cmd[0] == "mdi":
        c.mode(linuxcnc.MODE_MDI)
        c.wait_complete()
        c.mdi(" ".join(cmd[1:]))
        run_until_done(k, lambda: s.interp_state == linuxcnc.INTERP_IDLE and s.queue == 0 and s.inpos, 120)
    elif cmd[0] == "jog":
        c.mode(linuxcnc.MODE_MANUAL)
        c.wait_complete()
        c.teleop_enable(0)
        c.wait_complete()
        vel = float(cmd[1])
        d = [float(x) for x in cmd[2:8]]
        big = max(abs(x) for x in d)
        for j in range(6):
            if d[j] != 0.0:
                c.jog(linuxcnc.JOG_INCREMENT, True, j, vel * abs(d[j]) / big, d[j])
        run_until_done(k, lambda: all(s.joint[j]["inpos"] for j in range(6)), 120)
    else:
        fail("unknown path command: " + " ".join(cmd))
errors()
out.close()
print("drive.py: done", flush=True)

#!/usr/bin/env python3
"""Generates tools/data/demo_flight.csv, the sample flight that ships with Pacifica and is the demo default.

The flight shows the sea from the viewpoints that stress an ocean renderer: a fast low pass at ~20 m
(waves close up, horizon at grazing angle), a steep climb to ~4000 m (detail must fade out smoothly with
distance), and a banked, slightly nose-down turn at altitude (the sea at steep angles and tilted horizons).
Controls (speed, pitch, roll) are smooth functions of time; heading follows from a coordinated turn
(turn rate = g * tan(roll) / speed) and position is integrated from speed, heading and pitch, so the
samples are physically consistent. Python 3 standard library only; the output is deterministic.

After the camera samples the file carries scene events (docs/FLIGHT_FORMAT.md, "Event records"), placed where
the camera sees them:
  - explosions: one ahead and right of the low pass at 3 s, one near the first ship at 9 s, and a larger one
    in the sea the camera looks down on from ~4000 m in the banked turn at 46 s;
  - two ships at 10 m/s, each in a steady 0.5 deg/s turn so their wakes curve, with tracks that begin 120 s
    before the camera's start so a wake already trails them at t = 0: "coaster" crosses 1-3 km ahead of the
    low pass (seen close up at a grazing angle; the camera flies over its older wake), "frigate" lies where
    the banked turn looks down (seen from 5-7.5 km from 46 s to the end, and on the horizon 12-15 km away in
    the low pass; the climb, pitched 35 deg up, sees no sea at all).

Usage: python3 tools/data/make_demo_flight.py [OUTPUT.csv]   (default: demo_flight.csv next to this script)
Format: docs/FLIGHT_FORMAT.md.
"""

import math
import os
import sys

GRAVITY = 9.80665  # m/s^2, standard gravity
DURATION_S = 60.0
SAMPLE_STEP_S = 0.5
SUBSTEPS = 100  # integration steps per output sample (5 ms)
START_POSITION = (0.0, 0.0, 20.0)  # metres, ENU
START_HEADING_DEG = 90.0  # east


def smoothstep(t, t0, t1):
    """0 before t0, 1 after t1, C1-smooth cubic in between."""
    if t <= t0:
        return 0.0
    if t >= t1:
        return 1.0
    u = (t - t0) / (t1 - t0)
    return u * u * (3.0 - 2.0 * u)


def speed_mps(t):
    # 150 m/s on the low pass, accelerating in the climb, bleeding some speed in the turn.
    return 150.0 + 130.0 * smoothstep(t, 14.0, 24.0) - 60.0 * smoothstep(t, 44.0, 54.0)


def pitch_deg(t):
    # Level pass, pull up to ~35 degrees, push over at ~4000 m, then dip the nose twice in the turn.
    climb = 35.0 * (smoothstep(t, 14.0, 17.5) - smoothstep(t, 40.0, 45.0))
    dip = -8.0 * math.sin(math.pi * (t - 45.0) / 10.0) ** 2 if t > 45.0 else 0.0
    return climb + dip


def roll_deg(t):
    # Wings level until the top of the climb, then roll right into a 50-60 degree bank.
    bank = 55.0 * smoothstep(t, 43.0, 47.0)
    wobble = 5.0 * math.sin(math.pi * (t - 47.0) / 6.5) if t > 47.0 else 0.0
    return bank + wobble


def heading_rate_deg(t):
    # Coordinated turn: horizontal lift component g*tan(roll) bends the path (right wing down -> right turn).
    return math.degrees(GRAVITY * math.tan(math.radians(roll_deg(t))) / speed_mps(t))


def velocity(t, heading):
    v = speed_mps(t)
    p = math.radians(pitch_deg(t))
    h = math.radians(heading)
    # Heading is clockwise from north: east = sin, north = cos.
    return (v * math.cos(p) * math.sin(h), v * math.cos(p) * math.cos(h), v * math.sin(p))


def simulate():
    """Returns rows (time, x, y, z, heading, pitch, roll), integrating with the midpoint rule."""
    rows = []
    x, y, z = START_POSITION
    heading = START_HEADING_DEG
    t = 0.0
    dt = SAMPLE_STEP_S / SUBSTEPS
    sample_count = int(round(DURATION_S / SAMPLE_STEP_S)) + 1
    for i in range(sample_count):
        t = i * SAMPLE_STEP_S
        rows.append((t, x, y, z, heading, pitch_deg(t), roll_deg(t)))
        for k in range(SUBSTEPS):
            ts = t + k * dt
            mid_heading = heading + 0.5 * dt * heading_rate_deg(ts)
            vx, vy, vz = velocity(ts + 0.5 * dt, mid_heading)
            x += vx * dt
            y += vy * dt
            z += vz * dt
            heading += dt * heading_rate_deg(ts + 0.5 * dt)
    return rows


# Scene events. Positions in metres (x east, y north, at sea level); times on the flight's clock (seconds).
# (time_s, x_m, y_m, strength); strength 1 = a nominal ~500 kg charge (docs/FLIGHT_FORMAT.md).
EXPLOSIONS = [
    # 3 s into the low pass the camera is at x = 450 m: 600 m ahead, 150 m right (14 deg off the nose), in
    # view until ~5.9 s when it passes abeam, so the ring wave grows over ~6 frames at 2 frames/s.
    (3.0, 1050.0, -150.0, 1.0),
    # A smaller near miss 200 m off the coaster's bow; the camera (x = 1350 m) is 1.3 km short of it, 23 deg
    # to the left, and keeps it in view until ~13.5 s.
    (9.0, 2580.0, 530.0, 0.5),
    # In the turn, in the sea the camera looks down on from ~4000 m (right half of the frame, the banked side),
    # 350 m north-east of the frigate: in view from 46 s to 56 s at 7.5 -> 6 km, so its larger ring is seen
    # spreading for 10 s.
    (46.0, 14450.0, -3400.0, 4.0),
]

SHIP_SPEED_MPS = 10.0
SHIP_TURN_RATE_DEG = 0.5  # deg/s, a gentle turn (radius ~1150 m at 10 m/s)
SHIP_HISTORY_S = 120.0  # tracks start this long before the camera, so wakes already exist at t = 0
SHIP_SAMPLE_STEP_S = 2.0  # 20 m chords: the polyline stays within 5 cm of the arc
# (id, reference time, position at that time, heading at that time (compass deg), turn rate (deg/s, + = right))
SHIPS = [
    # Crosses ahead of the low pass heading NNW, turning left: 2.7 km ahead (6 deg left) at 0 s, 0.7 km
    # (36 deg left) at 14 s. Its older wake crosses the camera's line (y = 0) at x ~ 2830 m (the ship was
    # there at -30.5 s), beyond the low pass: the camera looks along it and passes over it at ~330 m, climbing.
    ("coaster", 7.0, (2700.0, 350.0), 330.0, -SHIP_TURN_RATE_DEG),
    # Heading south-south-west and turning right, where the banked turn looks down: in view from 46 s to the
    # end (7.5 -> 5 km, right half of the frame), its whole curved wake with it until ~53 s. In the low pass it
    # sits on the horizon 12-15 km ahead, slightly right.
    ("frigate", 52.0, (14250.0, -3750.0), 200.0, SHIP_TURN_RATE_DEG),
]


def ship_track(t_ref, pos_ref, heading_ref, turn_rate, t0, t1, step):
    """Samples (t, x, y) of a constant-speed, constant-turn-rate track through pos_ref at t_ref (exact arcs)."""
    samples = []
    count = int(round((t1 - t0) / step)) + 1
    for i in range(count):
        t = t0 + i * step
        dt = t - t_ref
        h0 = math.radians(heading_ref)
        w = math.radians(turn_rate)
        if w == 0.0:
            dx, dy = SHIP_SPEED_MPS * dt * math.sin(h0), SHIP_SPEED_MPS * dt * math.cos(h0)
        else:
            # Integral of v*(sin h, cos h) with h = h0 + w*dt (compass heading: east = sin, north = cos).
            r = SHIP_SPEED_MPS / w
            dx = r * (math.cos(h0) - math.cos(h0 + w * dt))
            dy = r * (math.sin(h0 + w * dt) - math.sin(h0))
        samples.append((t, pos_ref[0] + dx, pos_ref[1] + dy))
    return samples


def ship_tracks(rows):
    t0, t1 = rows[0][0] - SHIP_HISTORY_S, rows[-1][0]
    return [(ship_id, ship_track(t_ref, pos, heading, rate, t0, t1, SHIP_SAMPLE_STEP_S))
            for ship_id, t_ref, pos, heading, rate in SHIPS]


def format_heading(h):
    # Round first, then wrap, so 359.9996 becomes "0.000" and never "360.000".
    r = round(h % 360.0, 3) % 360.0
    return f"{r:.3f}"


def write_csv(path, rows, ships):
    lines = [
        "# Pacifica demo flight: low pass over the sea, climb to ~4000 m, banked turn.",
        "# Generated by tools/data/make_demo_flight.py - edit the script, not this file.",
        "# Format: docs/FLIGHT_FORMAT.md (x east, y north, z up, metres; degrees).",
        "time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg",
    ]
    for t, x, y, z, h, p, r in rows:
        lines.append(f"{t:.1f},{x:.2f},{y:.2f},{z:.2f},{format_heading(h)},{p:.3f},{r:.3f}")
    lines.append("# Explosions at sea level: explosion,time_s,x_m,y_m,strength (1 = a nominal ~500 kg charge).")
    for t, x, y, strength in EXPLOSIONS:
        lines.append(f"explosion,{t:.1f},{x:.2f},{y:.2f},{strength:g}")
    for ship_id, track in ships:
        lines.append(f"# Ship '{ship_id}' at sea level, {SHIP_SPEED_MPS:g} m/s: ship,id,time_s,x_m,y_m.")
        for t, x, y in track:
            lines.append(f"ship,{ship_id},{t:.1f},{x:.2f},{y:.2f}")
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def main(argv):
    if len(argv) > 2:
        sys.stderr.write("usage: make_demo_flight.py [OUTPUT.csv]\n")
        return 2
    here = os.path.dirname(os.path.abspath(__file__))
    out = argv[1] if len(argv) == 2 else os.path.join(here, "demo_flight.csv")
    rows = simulate()
    ships = ship_tracks(rows)
    write_csv(out, rows, ships)
    zs = [r[3] for r in rows]
    sys.stdout.write(f"wrote {out}: {len(rows)} samples, z {min(zs):.1f}..{max(zs):.1f} m, "
                     f"{len(EXPLOSIONS)} explosions, {len(ships)} ships "
                     f"({', '.join(f'{i}: {len(t)} samples' for i, t in ships)})\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

"""Outside check, audit 8: the JSON's joint entries against finite differences of positions alone.

FORMAT.md section 2 promises ``sliders[]`` and ``slots[]`` entries with ``slip_velocity`` and
``slip_acceleration`` (of the block, or pin, relative to the guide, along the path's direction at this
instant, signed; counter-clockwise about K on a circular path) and ``coriolis`` (2 omega_guide x V_rel),
and ``contacts[]`` entries whose ``slip_velocity`` is (v_a(P) - v_b(P)) . t with t the common normal u
(from a's centre of curvature towards b's) turned +90 degrees (section 5). test_zoo checks every point's
and link's rates against finite differences; nothing checked these entries so. Here they are computed
from the to_dict() positions and link angles of five poses along the driver, with none of velpoly's
relations: the block's point in the guide's own frame, s = Rot(-theta_guide) (X_block - X_guide point),
V_rel = Rot(theta_guide) ds/dt and A_rel = Rot(theta_guide) d2s/dt2 (fourth-order differences; a slider
driver's pose is its displacement u: d/dt = u' d/du, d2/dt2 = u'^2 d2/du2 + u'' d/du).

Audit 8 found nothing wrong here: on 9945c0a every joint entry of the 600 generated specimens of zoo seed 8
(every kind) agrees to 1e-6 of the largest speed and 1e-4 of the largest acceleration. This file is the
guard (57 specimens, one of each variant): with the single-pose Coriolis term of motion._relative1 reversed
or halved, its slip acceleration's y part reversed, or a contact's slip taken as v_b - v_a, it fails.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import velpoly

from zoo import each

SEED, COUNT = 20261125, 57   # test_zoo's first specimens: one of every (kind, variant)


def _rot(v, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _key(d, p, link):
    return p if p in d["points"] else f"{p}@{link}"


def _poses(sol):
    """Five poses along the driver: (the Sweep, step h, driver rate, driver rate's rate)."""
    m, drv = sol.mechanism, sol.mechanism.driver
    steps = np.array([-2.0, -1.0, 0.0, 1.0, 2.0])
    if drv.is_slider:   # a step small beside the shortest distance between points (a short crank)
        xy = np.array(list(m.points.values()), float)
        gaps = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
        h = 2e-4 * gaps[np.triu_indices(len(xy), 1)].min()
        return velpoly.sweep(m, steps * h), h, drv.speed, drv.accel
    h = 2e-4
    return velpoly.sweep(m, sol.driver_angle + steps * math.degrees(h)), h, drv.omega, drv.alpha


def _rates(x, h, rate, accel):
    """d/dt and d2/dt2 at the middle of five samples h apart in the driver's variable."""
    d1 = (-x[4] + 8 * x[3] - 8 * x[1] + x[0]) / (12 * h)
    d2 = (-x[4] + 16 * x[3] - 30 * x[2] + 16 * x[1] - x[0]) / (12 * h * h)
    return d1 * rate, d2 * rate ** 2 + d1 * accel


def _relative(spec, d, w, block, guide, point, h, rate, accel):
    """V_rel, A_rel of the block's point in the guide's frame, from the poses; None if the guide has
    no other point to measure from."""
    others = [q for q in spec["links"][guide]["points"] if q != point]
    if not others:
        return None
    theta = np.unwrap(np.asarray(w.angle[guide], float), period=360.0)
    x = np.asarray(w.position[_key(d, point, block)], float) - np.asarray(w.position[_key(d, others[0], guide)], float)
    s = np.array([_rot(x[i], -theta[i]) for i in range(5)])
    v, a = _rates(s, h, rate, accel)
    return _rot(v, theta[2]), _rot(a, theta[2])


def _tangent(spec_joint, d, block, guide, point):
    """The path's unit direction now: counter-clockwise about K, or the drawn direction (the pose is the drawn one)."""
    pts = d["points"]
    if "centre" in spec_joint:
        r = np.subtract(pts[_key(d, point, block)]["position"], pts[_key(d, spec_joint["centre"], guide)]["position"])
        return np.array([-r[1], r[0]]) / np.hypot(*r)
    if "angle" in spec_joint:
        return _rot((1.0, 0.0), spec_joint["angle"])
    p, q = spec_joint["along"]
    r = np.subtract(pts[_key(d, q, guide)]["position"], pts[_key(d, p, guide)]["position"])
    return r / np.hypot(*r)


def _joint_errors(spec, sol):
    """Each joint entry's disagreement with the differences, relative to the largest speed (acceleration)."""
    d = sol.to_dict()
    w, h, rate, accel = _poses(sol)
    assert len(w.angles) == 5, w.stopped
    vmax = max(np.hypot(*p["velocity"]) for p in d["points"].values())
    amax = max(max(np.hypot(*p["acceleration"]) for p in d["points"].values()), vmax * vmax / sol.mechanism.size)
    out = []
    joints = [("sliders", e, e["block"], e["guide"], e["point"]) for e in d["sliders"]] + \
             [("slots", e, e["link"], e["slot"], e["pin"]) for e in d.get("slots", [])]
    for table, e, block, guide, point in joints:
        sj = next(j for j in spec[table] if j.get("point", j.get("pin")) == point
                  and j.get("block", j.get("link")) == block)
        rel = _relative(spec, d, w, block, guide, point, h, rate, accel)
        if rel is None:
            continue
        v_rel, a_rel = rel
        t = _tangent(sj, d, block, guide, point)
        omega = d["links"][guide]["omega"]
        out.append((table, "slip_velocity", abs(v_rel @ t - e["slip_velocity"]) / vmax))
        out.append((table, "slip_acceleration", abs(a_rel @ t - e["slip_acceleration"]) / amax))
        coriolis = 2 * omega * np.array([-v_rel[1], v_rel[0]])
        out.append((table, "coriolis", float(np.hypot(*(coriolis - e["coriolis"]))) / amax))
    for e in d["contacts"]:
        out.append(("contacts", "slip_velocity", _contact_error(spec, d, e) / vmax))
    return out


def _contact_error(spec, d, e):
    """|(v_a(P) - v_b(P)) . t - slip_velocity|, each v from another point of its link and its omega (rigid body,
    written out here), u from the centres of curvature as section 5 says."""
    a, b = e["links"]
    pts = d["points"]
    at = np.asarray(pts[f"{e['point']}@{a}"]["position"])

    def v(link):
        q = pts[_key(d, spec["links"][link]["points"][0], link)]
        r = at - np.asarray(q["position"])
        return np.asarray(q["velocity"]) + d["links"][link]["omega"] * np.array([-r[1], r[0]])

    ca, cb = next(c for c in spec["contacts"] if c["point"] == e["point"])["centres"]
    centre_a = None if ca == "flat" else np.asarray(pts[_key(d, ca, a)]["position"])
    centre_b = None if cb == "flat" else np.asarray(pts[_key(d, cb, b)]["position"])
    u = (centre_b if centre_b is not None else at) - (centre_a if centre_a is not None else at)
    u = u / np.hypot(*u)
    return abs((v(a) - v(b)) @ np.array([-u[1], u[0]]) - e["slip_velocity"])


def test_joint_entries_are_the_finite_differences_of_positions():
    checked = {}
    for sp in each(SEED, COUNT):
        sol = sp.drawn
        m = sol.mechanism
        if not (m.sliders or m.slots or m.contacts) or any(c.centres is None for c in m.contacts):
            continue
        for table, what, err in _joint_errors(sp.mech, sol):
            checked[table] = checked.get(table, 0) + 1
            assert err <= (1e-6 if what == "slip_velocity" else 1e-4), (sp.kind, table, what, err)
    assert checked.get("sliders", 0) >= 60 and checked.get("slots", 0) >= 6 and checked.get("contacts", 0) >= 8, checked

"""Measure the space diagram's driver arrows/values and link numbers over zoo(2026, 60), full and poles sheets,
both styles. Usage: PYTHONPATH=<tree> python3 benchmarks/space_marks.py [--zoo SEED,COUNT] [i or i:sheet:style ...]
(prints per-case findings and totals (a link number on its own bar is counted as on_own_bar, not on_line), and the length of each driver value's leader in cm of paper, 0 where it
stands beside its arrow; --zoo measures another zoo, e.g. --zoo 7,40, the default 2026,60)."""
import sys, os, json
sys.path.insert(0, os.path.join(os.environ["PYTHONPATH"], "tests"))
import numpy as np
from shapely.geometry import Polygon, LineString, Point, box
from shapely.ops import nearest_points, unary_union
import velpoly
from zoo import zoo
from test_space_marks import on_own_bar
from velpoly.render import sheet as S
from velpoly.render import displacement as D
from velpoly.render.labels import placer
from velpoly.render.style import get_style, rc_context
from velpoly.render.canvas import per_cm

CAUGHT = []
_orig = S.draw_mechanism
def _wrap(sol, ax=None, **kw):
    art = _orig(sol, ax, **kw)
    CAUGHT.append((ax, art))
    return art
S.draw_mechanism = _wrap
from velpoly.render import kennedy as K
K.draw_mechanism = _wrap

def geom_of_patch(p):
    polys = [Polygon(v) for v in p.get_path().to_polygons() if len(v) >= 3]
    return unary_union([q.buffer(0) for q in polys]) if polys else None

def measure(sol, sheet, style):
    CAUGHT.clear()
    st = get_style(style)
    with rc_context(st):
        fig = S.render(sol, sheet, st).figure
        ax, art = CAUGHT[0]
        pl = placer(ax)
        r = pl.renderer
        axbb = ax.bbox
        out = {"out": [], "on_line": [], "on_own_bar": [], "overlap": [], "far_number": [], "leader_cross": [], "small": [], "arrow_cross": [],
               "point_on_link": [], "point_on_line": [], "value_leader": []}
        bodies = {**art.bodies, **getattr(art, "seen", {})}   # a plate beneath every link: its outline (its area is
        #                                                      the ground the marks over it stand on)
        for a in art.get("sliders", []):
            g = a.get_gid() or ""
            if g.startswith("block-"):
                bodies[g[6:]] = geom_of_patch(a)
        # driver arrows and values in view
        for a in art.get("driver", []):
            if a.figure is None:   # placed again since (a later leader crossed it): the new one is in pl.labels
                continue
            bb = a.get_window_extent(r)
            if bb.x0 < axbb.x0 - 0.5 or bb.x1 > axbb.x1 + 0.5 or bb.y0 < axbb.y0 - 0.5 or bb.y1 > axbb.y1 + 0.5:
                out["out"].append(a.get_gid())
        drv = sol.mechanism.driver
        mine_link = drv.link if not drv.is_slider else next(s.block for s in sol.mechanism.sliders if s.point == drv.slider)
        from matplotlib.lines import Line2D
        crossed = dict(bodies)   # a slider driver's arrows may run over its block's guide plate, off the slotted bar
        if drv.is_slider:
            crossed.update({k: art.guide_bars[k] for s in sol.mechanism.sliders if s.point == drv.slider
                            for k in [s.guide] if k in getattr(art, "guide_bars", {})})
        for a in art.get("driver", []):
            if isinstance(a, Line2D) and a.figure is not None:
                xy = np.column_stack(a.get_data())
                if len(xy) >= 2 and any(LineString(xy).intersects(g) for k, g in crossed.items() if k != mine_link and g is not None):
                    out["arrow_cross"].append(a.get_gid())
        texts = [p for p in pl.labels]
        boxes = {id(p.text): pl.box_of(p.text, pad=0.0) for p in texts}
        mine = [p for p in texts if (p.text.get_gid() or "").startswith(("driver-label", "link-number-"))]
        for p in mine:
            gid = p.text.get_gid()
            b = boxes[id(p.text)]
            if gid.startswith("link-number-") and p.text.get_bbox_patch() is not None:
                p.text.update_bbox_position_size(r)
                e = p.text.get_bbox_patch().get_window_extent(r)
                (x0, y0), (x1, y1) = ax.transData.inverted().transform([[e.x0, e.y0], [e.x1, e.y1]])
                b = box(min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))
            lk = gid[len("link-number-"):] if gid.startswith("link-number-") else None
            own = bodies.get(lk) if lk else None
            # on a line: a soft obstacle under it (a number on its own bar is on its own link, not on a line)
            if pl.soft_hits(b):
                out["on_own_bar" if on_own_bar(ax, art, gid, b) else "on_line"].append(gid)
            if any(b.intersects(boxes[id(q.text)]) for q in texts if q is not p):
                out["overlap"].append(gid)
            if gid.startswith("driver-label") and p.text.get_fontsize() < st.small_size - 1e-9:
                out["small"].append(gid)
            if lk and own is not None:
                d_own = b.distance(own)
                guides = {s.guide for s in sol.mechanism.sliders if s.block == lk}   # a block lies in its guide
                others = [(k, b.distance(g)) for k, g in bodies.items() if k != lk and k not in guides and g is not None]
                if others and min(d for _, d in others) < d_own - 1e-12 or any(b.intersects(getattr(art, "guide_bars", {}).get(k, bodies[k])) for k in guides if k in bodies):
                    out["far_number"].append(gid)
                if p.leader is not None:
                    xy = np.column_stack(p.leader.get_data())
                    ln = LineString(xy).difference(own.buffer(1e-9 * (own.length + 1)))
                    if any(ln.intersects(g) for k, g in bodies.items() if k != lk and k not in guides and g is not None):
                        out["leader_cross"].append(gid)
        # each driver value's leader in cm of paper (0 beside its arrow, no leader): gid=length
        for p in texts:
            gid = p.text.get_gid() or ""
            if gid.startswith("driver-label"):
                n = 0.0 if p.leader is None else LineString(np.column_stack(p.leader.get_data())).length / per_cm(ax)
                out["value_leader"].append(f"{gid}={n:.2f}")
        # point labels on a link's or block's outline, or over a link that does not carry the point
        for p in texts:
            gid = p.text.get_gid() or ""
            if not gid.startswith("label-point-"):
                continue
            b = boxes[id(p.text)]
            name = gid[len("label-point-"):]
            carriers = set(sol.mechanism.carriers.get(name, ()))
            if any(g is not None and (b.intersects(g.boundary) or k not in carriers and b.intersects(g))
                   for k, g in bodies.items()):
                out["point_on_link"].append(gid)
            if pl.soft_hits(b):   # on a line: an outline, slot, path, guide or Kennedy line, hatched ground
                out["point_on_line"].append(gid)
    return out

if __name__ == "__main__":
    args = sys.argv[1:]
    seed, count = 2026, 60
    if args[:1] == ["--zoo"]:
        seed, count = map(int, args[1].split(","))
        args = args[2:]
    Z = zoo(seed, count)
    specs = [a.split(":") for a in args] or [[str(i)] for i in range(len(Z))]   # i or i:sheet:style
    tot = {}
    cases, leaders = 0, []
    for spec in specs:
        i = int(spec[0])
        sol = velpoly.solve(velpoly.load(Z[i].mech))
        for sheet in spec[1:2] or ("full", "poles"):
            for style in spec[2:3] or ("textbook", "slides"):
                try:
                    res = measure(sol, sheet, style)
                except Exception as e:
                    print(i, sheet, style, "ERROR", type(e).__name__, e)
                    continue
                cases += 1
                values = res.pop("value_leader")
                leaders += [float(v.split("=")[1]) for v in values]
                bad = {k: v for k, v in res.items() if v}
                long = [v for v in values if float(v.split("=")[1]) > 1.0]
                if long:
                    bad["long_leader"] = long
                if bad:
                    print(i, sheet, style, Z[i].kind, json.dumps(bad), flush=True)
                for k, v in res.items():
                    tot[k] = tot.get(k, 0) + len(v)
    print("cases", cases, "TOTAL", json.dumps(tot))
    lead = np.array(leaders)
    print("driver values", len(lead), "leader cm: mean %.2f, max %.2f, over 1 cm %d, over 2 cm %d, sum %.1f" % (
        lead.mean(), lead.max(), (lead > 1).sum(), (lead > 2).sum(), lead.sum()) if len(lead) else "no driver values")

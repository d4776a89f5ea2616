#!/usr/bin/env python3
"""Writes big_loop.yaml: a ring corridor around a building block, 92 m x 58 m outside,
about 290 m per lap on its centre line (issue #16).

  y ^ 58 +----------------------------------------+   outer wall (a polyline)
         |  north corridor, 2.8 m                 |
         |   +--------------------------------+   |
         | W |        building block           | E |  the block is one polygon (solid)
         |2.5|   x 2.5 .. 89, y 2.6 .. 55.2    |3.0|
         |   +--------------------------------+   |
         |  south corridor, 2.6 m                 |
       0 +----------------------------------------+--> x (0 .. 92)

The four corridors differ in width, and their walls carry features at irregular
intervals, different on every side, so that scan matching has structure along each
corridor and no two stretches look the same:
  niche  (1.2 x 0.3 m door niche), alcove (2-2.5 m wide, 0.6-0.8 m deep),
  lobby  (3-4 m wide, 2.5-3.5 m deep opening off the corridor),
  store  (1.2 m x 2.5 m closet whose door, on the wall line, opens and closes),
  pillar (0.3 m square, protruding into the corridor).
Boxes stand in lobbies and alcoves (off the driven line); two of them move.
Places: the four corners of the centre line and the middle of each side; the roadmap is
the ring through them. A lap is the path sw -> se -> ne -> nw -> sw.
Run: python3 worlds/make_big_loop.py > worlds/big_loop.yaml"""

W, H = 92.0, 58.0
WIDTH = {"s": 2.6, "e": 3.0, "n": 2.8, "w": 2.5}  # corridor widths
X0, X1 = WIDTH["w"], W - WIDTH["e"]               # building block
Y0, Y1 = WIDTH["s"], H - WIDTH["n"]
KINDS = {"niche": (1.2, 0.3), "pillar": (0.3, 0.3), "store": (1.2, 2.5)}  # width, depth
# Features per wall: (distance along the wall from its first corner, counter-clockwise,
# kind, width, depth); width and depth default to KINDS[kind].
OUTER = {
    "s": [(6, "pillar"), (11, "niche"), (17.5, "alcove", 2.0, 0.8), (24, "pillar"),
          (30, "lobby", 3.0, 3.0), (38.5, "niche"), (45, "pillar"), (51, "store"),
          (58, "niche"), (63.5, "pillar"), (70, "alcove", 2.5, 0.6), (77, "niche"),
          (83, "pillar")],
    "e": [(5, "niche"), (12, "pillar"), (19, "lobby", 4.0, 2.5), (28, "pillar"),
          (34, "niche"), (41, "store"), (48, "pillar")],
    "n": [(6, "alcove", 2.0, 0.8), (14, "pillar"), (21, "niche"), (33, "pillar"),
          (40, "lobby", 3.0, 3.5), (52, "niche"), (58, "pillar"), (66, "niche"),
          (73, "store"), (80, "pillar"), (86, "niche")],
    "w": [(7, "pillar"), (15, "niche"), (23, "alcove", 2.0, 0.6), (33, "pillar"),
          (42, "niche"), (50, "pillar")],
}
INNER = {
    "s": [(4, "niche", 1.0, 0.3), (13, "pillar"), (27, "niche", 1.5, 0.5), (40, "pillar"),
          (55, "niche", 1.0, 0.3), (66, "pillar"), (78, "niche", 2.0, 0.5)],
    "e": [(6, "pillar"), (17, "niche", 1.0, 0.3), (30, "pillar"), (44, "niche", 1.5, 0.5)],
    "n": [(9, "niche"), (22, "pillar"), (36, "niche", 2.0, 0.5), (49, "pillar"),
          (61, "niche"), (74, "pillar")],
    "w": [(10, "niche", 1.5, 0.5), (24, "pillar"), (38, "niche"), (47, "pillar")],
}
STORE_CLOSED = {"s": [[0, 1200], [3000, 4800]], "e": [[600, 2400], [5400, 7200]],
                "n": [[200, 3600]]}  # closed intervals (s) of the store doors


def pt(p):
    return f"[{round(p[0], 3):g}, {round(p[1], 3):g}]"


def sides(corners):
    """(side, start corner, unit direction, length) of a counter-clockwise rectangle."""
    out = []
    for k, side in enumerate("senw"):
        (ax, ay), (bx, by) = corners[k], corners[(k + 1) % 4]
        length = abs(bx - ax) + abs(by - ay)
        out.append((side, (ax, ay), ((bx - ax) / length, (by - ay) / length), length))
    return out


def walk(corners, features, outward, margin):
    """Points of the wall around `corners` with the recesses cut in, plus pillar polygons
    and store doors. outward: recesses go to the right of the direction of travel (outer
    wall) or to its left (block); pillars go the other way, into the corridor."""
    points, pillars, doors = [], [], []
    for side, (ax, ay), (dx, dy), length in sides(corners):
        ox, oy = (dy, -dx) if outward else (-dy, dx)  # away from the corridor

        def at(s, d=0.0):  # the point s along this side, d away from the corridor
            return (ax + dx * s + ox * d, ay + dy * s + oy * d)

        points.append((ax, ay))
        last = margin
        for f in features[side]:
            s, kind = f[0], f[1]
            w, d = f[2:] if len(f) > 2 else KINDS[kind]
            assert s >= last and s + w <= length - margin, f"{side} {s} {kind} overlaps"
            last = s + w + 0.3
            if kind == "pillar":
                pillars.append([at(s), at(s + w), at(s + w, -d), at(s, -d)])
                continue
            points += [at(s), at(s, d), at(s + w, d), at(s + w)]
            if kind == "store":
                doors.append((f"store_{side}", at(s), at(s + w)))
    return points, pillars, doors


def main():
    print("# Big loop, a ring corridor around a 86.5 m x 52.6 m block (about 290 m per lap); "
          "generated by make_big_loop.py (edit that, not this).")
    print("clearance_m: 0.3")
    outer = [(0, 0), (W, 0), (W, H), (0, H)]
    block = [(X0, Y0), (X1, Y0), (X1, Y1), (X0, Y1)]
    # Margins keep features out of the corner squares of the ring.
    out_pts, out_pillars, doors = walk(outer, OUTER, True, 4.0)
    in_pts, in_pillars, in_doors = walk(block, INNER, False, 1.5)
    assert not in_doors
    print("walls:")
    print(f"  - polyline: [{', '.join(pt(p) for p in out_pts + [outer[0]])}]  # outer wall")
    print(f"  - polygon: [{', '.join(pt(p) for p in in_pts)}]  # building block")
    for poly in out_pillars + in_pillars:
        print(f"  - polygon: [{', '.join(pt(p) for p in poly)}]  # pillar")
    print("doors:")
    for name, a, b in doors:
        print(f"  - {{name: {name}, from: {pt(a)}, to: {pt(b)}, "
              f"closed_s: {STORE_CLOSED[name[-1]]}}}")
    print("boxes:")  # in the south and east lobbies and the north-east alcove
    print("  - {name: bench, center: [31.5, -2.2], size: [1.8, 0.5]}")
    print(f"  - {{name: cart, center: {pt((W + 1.2, 20.2))}, size: [0.8, 1.0], "
          f"moves: [{{t_s: 1800, center: {pt((W + 1.2, 21.8))}}}]}}")
    print(f"  - {{name: bin, center: {pt((85.0, H + 0.45))}, size: [0.5, 0.5], "
          f"moves: [{{t_s: 300, center: {pt((84.6, H + 0.45))}}}, "
          f"{{t_s: 2400, center: {pt((85.3, H + 0.45))}}}]}}")
    print("places:")  # on the centre line of the ring
    xw, xe = X0 / 2, (X1 + W) / 2
    ys, yn = Y0 / 2, (Y1 + H) / 2
    ring = [("sw", xw, ys), ("s_mid", W / 2, ys), ("se", xe, ys), ("e_mid", xe, H / 2),
            ("ne", xe, yn), ("n_mid", W / 2, yn), ("nw", xw, yn), ("w_mid", xw, H / 2)]
    for name, x, y in ring:
        print(f"  - {{name: {name}, at: {pt((x, y))}}}")
    print("roadmap:")
    for k, (name, _, _) in enumerate(ring):
        print(f"  - [{name}, {ring[(k + 1) % len(ring)][0]}]")


if __name__ == "__main__":
    main()

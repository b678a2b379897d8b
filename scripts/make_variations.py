#!/usr/bin/env python3
"""Writes the hand-made variations of the paper's five models (examples/variations/).

Each model is described by a few meaningful dimensions; the base dimensions reproduce
examples/paper/<model>.scad exactly, and each variation (bench, stool, ... in the spirit of
the paper's prompts) is the same program with other numbers. A part a variation does without
gets zero size. Run from the repository root; the output is committed, so this is only
needed to change the variations.
"""
import os

def num(v):
    v = round(v, 6)
    return str(int(v)) if v == int(v) else repr(v)

def box(name, mn, sz):
    return ("box", name, mn, sz)

def cyl(name, axis, mn, sz, r2=None):
    return ("cyl", name, mn, sz, axis, r2)

ROT = {0: "rotate([0, 90, 0]) ", 1: "rotate([90, 0, 0]) ", 2: ""}

def paper(title, parts):
    out = [f"// {title}", ""]
    for p in parts:
        mn, sz = p[2], p[3]
        c = [mn[i] + sz[i] / 2 for i in range(3)]
        out.append(f"// {p[1]}")
        head = f"translate([{num(c[0])}, {num(c[1])}, {num(c[2])}]) scale([{num(sz[0])}, {num(sz[1])}, {num(sz[2])}]) "
        if p[0] == "box":
            out.append(head + "cube(1, center=true);")
        elif p[5] is None:
            out.append(head + ROT[p[4]] + "cylinder(h=1, r=0.5, center=true);")
        else:
            out.append(head + ROT[p[4]] + f"cylinder(h=1, r1=0.5, r2={num(p[5])}, center=true);")
    return "\n".join(out) + "\n"

def natural(title, parts):
    out = [f"// {title}", ""]
    for p in parts:
        mn, sz = p[2], p[3]
        out.append(f"// {p[1]}")
        out.append(f"translate([{num(mn[0])}, {num(mn[1])}, {num(mn[2])}]) cube([{num(sz[0])}, {num(sz[1])}, {num(sz[2])}]);")
    return "\n".join(out) + "\n"

def chair(W, D, T, L, H, B, A, arms=True, back=True):
    z = lambda s: s if True else None
    return [
        box("left front leg", [-W/2, -D/2, -H], [L, L, H]),
        box("right front leg", [W/2-L, -D/2, -H], [L, L, H]),
        box("left back leg", [-W/2, D/2-L, -H], [L, L, H]),
        box("right back leg", [W/2-L, D/2-L, -H], [L, L, H]),
        box("seat", [-W/2, -D/2, 0], [W, D, T]),
        box("back", [-W/2, D/2-L, T], [W, L, B] if back else [0, 0, 0]),
        box("left arm", [-W/2, -D/2, T], [L, D-L, A] if arms else [0, 0, 0]),
        box("right arm", [W/2-L, -D/2, T], [L, D-L, A] if arms else [0, 0, 0]),
    ]

def table(W, D, T, L, H, i, S, floor=-40):
    return [
        box("table top", [-W/2, -D/2, floor+H], [W, D, T]),
        box("table middle", [-W/2+i, -D/2+i, floor+H/2], [W-2*i, D-2*i, S]),
        box("left back leg", [-W/2+i, D/2-i-L, floor], [L, L, H]),
        box("right back leg", [W/2-i-L, D/2-i-L, floor], [L, L, H]),
        box("left front leg", [-W/2+i, -D/2+i, floor], [L, L, H]),
        box("right front leg", [W/2-i-L, -D/2+i, floor], [L, L, H]),
    ]

def car(W, Lf, Lm, Lb, Hlow, Hmid, Dw, Ww, zc=-17.5):
    y0 = -(Lf + Lm + Lb) / 2
    yb = y0 + Lf + Lm
    yf = y0 + Lf / 2
    wheel = lambda n, x, y: cyl(n, 0, [x, y - Dw/2, zc - Dw/2], [Ww, Dw, Dw])
    return [
        box("back chassis", [-W/2, yb, zc], [W, Lb, Hlow]),
        box("mid chassis", [-W/2, y0+Lf, zc], [W, Lm, Hmid]),
        box("front chassis", [-W/2, y0, zc], [W, Lf, Hlow]),
        wheel("left back wheel", -W/2-Ww, yb),
        wheel("right back wheel", W/2, yb),
        wheel("left front wheel", -W/2-Ww, yf),
        wheel("right front wheel", W/2, yf),
    ]

def camera(W, Db, H, Wg, Dg, Dl, Ll, lx, Wf, Hf, yfront=30):
    return [
        box("body", [-W/2, yfront, -H/2], [W, Db, H]),
        box("grip", [-W/2, yfront-Dg, -H/2], [Wg, Dg, H]),
        cyl("lens", 1, [lx-Dl/2, yfront-Ll, -Dl/2], [Dl, Ll, Dl]),
        box("flash", [lx-Wf/2, yfront, H/2], [Wf, Db, Hf]),
    ]

def bottle(Db, Hb, Hc, Dh, Hh, r2, floor=-50):
    return [
        cyl("body", 2, [-Db/2, -Db/2, floor], [Db, Db, Hb]),
        cyl("body two (a cone narrowing upward)", 2, [-Db/2, -Db/2, floor+Hb], [Db, Db, Hc], r2),
        cyl("head", 2, [-Dh/2, -Dh/2, floor+Hb+Hc], [Dh, Dh, Hh]),
    ]

MODELS = {
    "chair": (chair, dict(W=100, D=100, T=15, L=15, H=70, B=70, A=30), {
        "bench": dict(W=160, D=45, T=5, L=6, H=45, B=40, A=30, arms=False),
        "stool": dict(W=45, D=45, T=4, L=4, H=75, B=70, A=30, arms=False, back=False),
        "bar_stool": dict(W=40, D=40, T=4, L=4, H=100, B=70, A=30, arms=False, back=False),
        "armchair": dict(W=90, D=85, T=12, L=10, H=40, B=60, A=25),
        "lounge": dict(W=80, D=110, T=10, L=8, H=25, B=50, A=20),
        "dining_chair": dict(W=45, D=45, T=4, L=4, H=45, B=45, A=30, arms=False),
    }),
    "table": (table, dict(W=100, D=100, T=10, L=10, H=70, i=5, S=10), {
        "coffee_table": dict(W=120, D=60, T=4, L=5, H=40, i=3, S=3),
        "desk": dict(W=140, D=70, T=4, L=6, H=72, i=2, S=3),
        "side_table": dict(W=45, D=45, T=3, L=4, H=55, i=2, S=3),
        "dining_table": dict(W=180, D=90, T=5, L=8, H=72, i=4, S=4),
        "bar_table": dict(W=60, D=60, T=4, L=6, H=105, i=5, S=4),
    }),
    "car": (car, dict(W=100, Lf=50, Lm=75, Lb=25, Hlow=30, Hmid=50, Dw=30, Ww=10), {
        "pickup": dict(W=110, Lf=60, Lm=60, Lb=90, Hlow=35, Hmid=70, Dw=40, Ww=12),
        "suv": dict(W=110, Lf=45, Lm=110, Lb=30, Hlow=40, Hmid=75, Dw=40, Ww=12),
        "sedan": dict(W=100, Lf=60, Lm=90, Lb=50, Hlow=28, Hmid=45, Dw=30, Ww=10),
        "van": dict(W=110, Lf=30, Lm=150, Lb=20, Hlow=40, Hmid=90, Dw=32, Ww=10),
        "sports_car": dict(W=105, Lf=70, Lm=70, Lb=50, Hlow=20, Hmid=35, Dw=32, Ww=12),
    }),
    "camera": (camera, dict(W=100, Db=20, H=60, Wg=25, Dg=20, Dl=50, Ll=50, lx=12.5, Wf=30, Hf=10), {
        "action_camera": dict(W=60, Db=30, H=45, Wg=10, Dg=5, Dl=25, Ll=10, lx=10, Wf=10, Hf=3),
        "film_camera": dict(W=140, Db=30, H=80, Wg=25, Dg=15, Dl=45, Ll=40, lx=0, Wf=30, Hf=15),
        "compact": dict(W=100, Db=25, H=60, Wg=15, Dg=8, Dl=35, Ll=20, lx=20, Wf=20, Hf=6),
        "dslr": dict(W=130, Db=40, H=95, Wg=35, Dg=30, Dl=70, Ll=80, lx=10, Wf=35, Hf=20),
        "instant_camera": dict(W=110, Db=45, H=110, Wg=20, Dg=10, Dl=50, Ll=25, lx=20, Wf=30, Hf=12),
    }),
    "bottle": (bottle, dict(Db=40, Hb=40, Hc=30, Dh=20, Hh=20, r2=0.2), {
        "wine_bottle": dict(Db=30, Hb=60, Hc=15, Dh=12, Hh=30, r2=0.2),
        "water_bottle": dict(Db=35, Hb=70, Hc=10, Dh=15, Hh=8, r2=0.25),
        "jug": dict(Db=60, Hb=50, Hc=20, Dh=25, Hh=10, r2=0.25),
        "flask": dict(Db=40, Hb=30, Hc=25, Dh=15, Hh=20, r2=0.2),
        "vase": dict(Db=50, Hb=40, Hc=40, Dh=30, Hh=15, r2=0.3),
    }),
}

def main():
    for name, (make, base, variations) in MODELS.items():
        model = open(f"examples/paper/{name}.scad").read()
        title = model.splitlines()[0][3:]
        assert paper(title, make(**base)) == model, f"base {name} does not reproduce examples/paper/{name}.scad"
        os.makedirs(f"examples/variations/paper_{name}", exist_ok=True)
        for v, dims in variations.items():
            with open(f"examples/variations/paper_{name}/{v}.scad", "w") as f:
                f.write(paper(title, make(**dims)))
    model = open("examples/chair.scad").read()
    title = model.splitlines()[0][3:]
    assert natural(title, chair(**MODELS["chair"][1])) == model, "base chair does not reproduce examples/chair.scad"
    os.makedirs("examples/variations/chair", exist_ok=True)
    for v, dims in MODELS["chair"][2].items():
        with open(f"examples/variations/chair/{v}.scad", "w") as f:
            f.write(natural(title, chair(**dims)))

main()

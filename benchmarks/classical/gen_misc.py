"""Problem generators for blocksworld, rovers, satellite, barman, visit-all and floor-tile.

One plain function per domain returning the PDDL problem text; the same
arguments (``seed`` included) always give the same text.
"""

from __future__ import annotations

import random

from benchmarks.classical.problem import connected_graph, fact, problem_text, towers

MODES = ["colour", "high_res", "low_res"]
SAT_MODES = ["image1", "infrared2", "spectrograph3", "thermograph4"]


def _tower_facts(stacks: list[list[str]]) -> list[str]:
    out = []
    for t in stacks:
        out += [fact("ontable", t[0]), fact("clear", t[-1])]
        out += [fact("on", t[k], t[k - 1]) for k in range(1, len(t))]
    return out


def blocksworld(blocks: int = 4, seed: int = 0) -> str:
    """IPC-2000 style: random towers at the start; the goal lists the ``on`` facts of other random towers."""
    rng = random.Random(seed)
    names = [chr(ord("a") + i) if blocks <= 26 else f"b{i}" for i in range(blocks)]
    start = towers(names, rng)
    while True:
        target = towers(names, rng)
        goal = [f for f in _tower_facts(target) if f.startswith("(on ")]
        if goal and sorted(map(tuple, target)) != sorted(map(tuple, start)):
            break
    init = _tower_facts(start) + ["(handempty)"]
    return problem_text("blocksworld", f"blocks-{blocks}-s{seed}", [(names, None)], init, sorted(goal),
                        comment=f"{blocks} blocks")


def _spanning(n: int, edges: list[tuple[int, int]], rng: random.Random) -> list[tuple[int, int]]:
    """A random spanning tree of the connected graph ``edges`` (random-order Kruskal)."""
    parent = list(range(n))

    def root(x: int) -> int:
        while parent[x] != x:
            x = parent[x]
        return x

    tree = []
    for e in rng.sample(edges, len(edges)):
        a, b = root(e[0]), root(e[1])
        if a != b:
            parent[a] = b
            tree.append(e)
    return sorted(tree)


def rovers(rovers: int = 1, waypoints: int = 4, objectives: int = 2, soil: int = 1, rock: int = 1,
           images: int = 1, seed: int = 0) -> str:
    """IPC-2002 style: a connected visibility map; each rover traverses a spanning tree of it and more."""
    rng = random.Random(seed)
    wp = [f"waypoint{i}" for i in range(waypoints)]
    rv = [f"rover{i}" for i in range(rovers)]
    obj = [f"objective{i}" for i in range(objectives)]
    visible = connected_graph(waypoints, 0.35, rng)
    init = [fact("visible", wp[i], wp[j]) for i, j in visible] + [fact("visible", wp[j], wp[i]) for i, j in visible]
    init += ["(at_lander general " + rng.choice(wp) + ")", "(channel_free general)"]
    caps = {c: [r for r in rv if rng.random() < 0.6] for c in ("soil", "rock", "imaging")}
    for c in caps:
        if not caps[c]:
            caps[c] = [rng.choice(rv)]
    cameras: list[str] = []
    supported: list[str] = []
    for r in rv:
        tree = _spanning(waypoints, visible, rng)
        trav = tree + [e for e in visible if e not in tree and rng.random() < 0.5]
        init += [fact("can_traverse", r, wp[i], wp[j]) for i, j in trav]
        init += [fact("can_traverse", r, wp[j], wp[i]) for i, j in trav]
        init += [fact("at", r, rng.choice(wp)), fact("available", r), fact("store_of", f"{r}store", r),
                 fact("empty", f"{r}store")]
        for c in ("soil", "rock"):
            if r in caps[c]:
                init.append(fact(f"equipped_for_{c}_analysis", r))
        if r in caps["imaging"]:
            init.append(fact("equipped_for_imaging", r))
            cam = f"camera{len(cameras)}"
            cameras.append(cam)
            modes = [m for m in MODES if rng.random() < 0.6] or [rng.choice(MODES)]
            supported += [m for m in modes if m not in supported]
            init += [fact("on_board", cam, r), fact("calibration_target", cam, rng.choice(obj))]
            init += [fact("supports", cam, m) for m in modes]
    for o in obj:
        seen = [w for w in wp if rng.random() < 0.4] or [rng.choice(wp)]
        init += [fact("visible_from", o, w) for w in seen]
    goal = []
    for c, k in (("soil", soil), ("rock", rock)):
        sites = rng.sample(wp, min(waypoints, k + rng.randint(0, 2)))
        init += [fact(f"at_{c}_sample", w) for w in sites]
        goal += [fact(f"communicated_{c}_data", w) for w in sites[:k]]
    pairs = [(o, m) for o in obj for m in sorted(supported)]
    goal += [fact("communicated_image_data", o, m) for o, m in rng.sample(pairs, min(images, len(pairs)))]
    objects = [(rv, "rover"), ([f"{r}store" for r in rv], "store"), (wp, "waypoint"), (cameras, "camera"),
               (MODES, "mode"), (["general"], "lander"), (obj, "objective")]
    name = f"rovers-r{rovers}-w{waypoints}-o{objectives}-g{soil}{rock}{images}-s{seed}"
    return problem_text("rover", name, objects, init, goal,
                        comment=f"{rovers} rover(s), {waypoints} waypoints, {objectives} objectives, "
                                f"goals: {soil} soil, {rock} rock, {images} image(s)")


def satellite(satellites: int = 1, instruments: int = 1, modes: int = 3, stars: int = 2, targets: int = 3,
              images: int = 2, seed: int = 0) -> str:
    """IPC-2002 style: up to ``instruments`` per satellite, each calibrated on a star."""
    rng = random.Random(seed)
    sats = [f"satellite{i}" for i in range(satellites)]
    mode = SAT_MODES[:modes]
    star = [f"star{i}" for i in range(stars)]
    tgt = [f"phenomenon{i}" for i in range(stars, stars + targets)]
    directions = star + tgt
    inst: list[str] = []
    supported: list[str] = []
    init = []
    goal = []
    for s in sats:
        for _ in range(rng.randint(1, instruments)):
            i = f"instrument{len(inst)}"
            inst.append(i)
            ms = [m for m in mode if rng.random() < 0.5] or [rng.choice(mode)]
            supported += [m for m in ms if m not in supported]
            init += [fact("on_board", i, s), fact("calibration_target", i, rng.choice(star))]
            init += [fact("supports", i, m) for m in ms]
        init += [fact("power_avail", s), fact("pointing", s, rng.choice(directions))]
        if rng.random() < 0.5:
            goal.append(fact("pointing", s, rng.choice(directions)))
    pairs = [(d, m) for d in tgt for m in mode if m in supported]
    goal += [fact("have_image", d, m) for d, m in rng.sample(pairs, min(images, len(pairs)))]
    objects = [(sats, "satellite"), (inst, "instrument"), (mode, "mode"), (directions, "direction")]
    name = f"satellite-s{satellites}-i{instruments}-m{modes}-t{targets}-g{images}-s{seed}"
    return problem_text("satellite", name, objects, init, goal,
                        comment=f"{satellites} satellite(s), {len(inst)} instrument(s), {images} images")


def barman(shots: int = 4, cocktails: int = 3, goals: int = 3, seed: int = 0) -> str:
    """IPC-2011 style: 3 ingredients, one shaker of two levels; the goal fills ``goals`` shots with cocktails."""
    rng = random.Random(seed)
    ingr = [f"ingredient{i}" for i in range(1, 4)]
    cock = [f"cocktail{i}" for i in range(1, cocktails + 1)]
    shot = [f"shot{i}" for i in range(1, shots + 1)]
    disp = [f"dispenser{i}" for i in range(1, 4)]
    levels = ["l0", "l1", "l2"]
    init = ["(ontable shaker1)", "(clean shaker1)", "(empty shaker1)", "(shaker-empty-level shaker1 l0)",
            "(shaker-level shaker1 l0)", "(next l0 l1)", "(next l1 l2)", "(handempty left)", "(handempty right)"]
    for s in shot:
        init += [fact("ontable", s), fact("clean", s), fact("empty", s)]
    init += [fact("dispenses", d, i) for d, i in zip(disp, ingr, strict=True)]
    for c in cock:
        a, b = rng.sample(ingr, 2)
        init += [fact("cocktail-part1", c, a), fact("cocktail-part2", c, b)]
    goal = [fact("contains", s, rng.choice(cock)) for s in shot[:goals]]
    objects = [(["shaker1"], "shaker"), (["left", "right"], "hand"), (shot, "shot"), (ingr, "ingredient"),
               (cock, "cocktail"), (disp, "dispenser"), (levels, "level")]
    return problem_text("barman", f"barman-s{shots}-c{cocktails}-g{goals}-s{seed}", objects, init, goal,
                        comment=f"{shots} shots, {cocktails} cocktails, {goals} goal shots")


def visitall(width: int = 3, height: int = 3, seed: int = 0) -> str:
    """IPC-2011 style: a ``width`` x ``height`` grid, every cell to visit; the robot starts at a random cell."""
    rng = random.Random(seed)
    cell = [[f"loc-x{x}-y{y}" for y in range(height)] for x in range(width)]
    init = []
    for x in range(width):
        for y in range(height):
            for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                if 0 <= x + dx < width and 0 <= y + dy < height:
                    init.append(fact("connected", cell[x][y], cell[x + dx][y + dy]))
    start = cell[rng.randrange(width)][rng.randrange(height)]
    init += [fact("at-robot", start), fact("visited", start)]
    places = [c for col in cell for c in col]
    return problem_text("grid-visit-all", f"visitall-{width}x{height}-s{seed}", [(places, "place")], init,
                        [fact("visited", p) for p in places], comment=f"{width} x {height} grid")


def floortile(rows: int = 3, columns: int = 3, robots: int = 2, seed: int = 0) -> str:
    """IPC-2011 style: rows 1..``rows`` are painted in a chequer pattern; row 0 stays unpainted."""
    rng = random.Random(seed)
    tile = [[f"tile_{i}-{j}" for j in range(1, columns + 1)] for i in range(rows + 1)]
    rob = [f"robot{k}" for k in range(1, robots + 1)]
    tiles = [t for row in tile for t in row]
    at = rng.sample(tiles, robots)
    init = []
    for r, t in zip(rob, at, strict=True):
        init += [fact("robot-at", r, t), fact("robot-has", r, rng.choice(["white", "black"]))]
    init += [fact("clear", t) for t in tiles if t not in at]
    init += ["(available-color white)", "(available-color black)"]
    for i in range(rows + 1):
        for j in range(columns):
            if i < rows:
                init += [fact("up", tile[i + 1][j], tile[i][j]), fact("down", tile[i][j], tile[i + 1][j])]
            if j + 1 < columns:
                init += [fact("right", tile[i][j + 1], tile[i][j]), fact("left", tile[i][j], tile[i][j + 1])]
    goal = [fact("painted", tile[i][j - 1], "white" if (i + j) % 2 == 0 else "black")
            for i in range(1, rows + 1) for j in range(1, columns + 1)]
    objects = [(rob, "robot"), (tiles, "tile"), (["white", "black"], "color")]
    return problem_text("floor-tile", f"floortile-{rows}x{columns}-r{robots}-s{seed}", objects, init, goal,
                        costs=True, comment=f"{rows} x {columns} tiles to paint, {robots} robot(s)")

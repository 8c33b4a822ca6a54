"""The kitchen's geometry, built in a PyBullet DIRECT client by our own code (seed 004 VIII).

A counter with two stacked drawers on prismatic joints (the tall sugar box
does not fit under the counter top when the top drawer closes), a stove
plate with a button, boxes (green block, sugar box, cracker box; the hard
problems add a mustard bottle, a soup can and a spam tin), a fixed camera,
and the Franka Panda from ``pybullet_data`` on a pedestal that slides along
a rail in front of the counter.  The hard problems add a **cabinet**: a box
on the left of the counter whose lid slides to the left to open it (a sliding
lid rather than the paper's hinged door, so that the top-down grasps reach
in).  The same builder makes the true world and the agent's model scene
(for collision checks and IK).

Frames: ``counter``, ``stove``, ``top`` and ``bottom`` (drawer trays, whose
origins move with the drawer joint), ``cabinet`` (fixed) and ``hand``.
Positions of movable objects are their box centres relative to a frame's
origin.  "Containers" are the frames that open and close: the drawers and,
when built, the cabinet; their states (m of travel) are kept in one dict.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from nowplan.belief.particles import Region
from nowplan.errors import require


def pybullet() -> Any:
    """``import pybullet`` without its build banner (printed by its C code when first imported).

    The banner goes to the process's file descriptors, not to ``sys.stdout``, so both are pointed
    at /dev/null for the import and C's buffers flushed before they are restored.
    """
    import sys

    if "pybullet" in sys.modules:
        return sys.modules["pybullet"]
    import ctypes
    import os

    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        os.dup2(null, 2)
        try:
            return require("pybullet", "kitchen")
        finally:
            try:
                ctypes.CDLL(None).fflush(None)
            except (OSError, AttributeError):  # no C library to flush (not on POSIX)
                pass
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, null):
            os.close(fd)

COUNTER_TOP = 0.60
FRONT_Y = 0.45  # the counter's front face
DRAWER_OPEN = 0.27  # how far an open drawer slides out (m)
DRAWERS = ("top", "bottom")
CABINET = "cabinet"
CABINET_CENTRE = np.array([-0.44, 0.66, COUNTER_TOP])  # the cabinet frame's origin (its floor's centre)
CABINET_HALF = (0.12, 0.15)  # interior half extents (x, y)
CABINET_WALL = 0.10  # wall height above the counter top
CABINET_OPEN = 0.26  # how far the open lid has slid to the left (m)
HARD_COUNTER = ((-0.26, 0.50), (0.28, 0.78))  # the counter left free by the cabinet and the stove
DRAWER_FLOOR = {"top": 0.38, "bottom": 0.14}
BASE_Z = 0.45
RAIL = (-0.45, 0.45)  # the pedestal's x range
CAMERA = np.array([0.0, -0.55, 1.55])
CAMERA_TARGET = np.array([0.0, 0.45, 0.45])
ARM_JOINTS = tuple(range(7))
EE_LINK = 11
HOME = (0.0, 0.0, -0.6, 0.0, -2.3, 0.0, 1.8, 0.8)  # base x, then the 7 arm joints

# box half extents of the movable objects
SIZES = {
    "green": (0.025, 0.025, 0.025),
    "sugar": (0.04, 0.025, 0.095),
    "cracker": (0.07, 0.025, 0.105),
    "mustard": (0.035, 0.025, 0.095),
    "soup": (0.035, 0.035, 0.07),
    "spam": (0.045, 0.03, 0.035),
}
COLOURS = {"green": (0.1, 0.8, 0.1, 1), "sugar": (0.9, 0.9, 0.2, 1), "cracker": (0.8, 0.2, 0.1, 1),
           "mustard": (0.95, 0.75, 0.1, 1), "soup": (0.7, 0.1, 0.1, 1), "spam": (0.2, 0.3, 0.8, 1)}
TALL = ("sugar", "cracker", "mustard")  # too tall for a closed drawer (and for the cabinet)


def containers(cabinet: bool) -> tuple[str, ...]:
    return (*DRAWERS, CABINET) if cabinet else DRAWERS


def frames_of(cabinet: bool) -> tuple[str, ...]:
    """The frames objects rest in (the hand aside)."""
    return ("counter", "stove", *containers(cabinet))


def frame_origin(frame: str, drawers: dict[str, float]) -> np.ndarray:
    """World position of a frame's origin given the drawers' joint positions."""
    if frame == "counter":
        return np.array([0.0, 0.0, COUNTER_TOP])
    if frame == "stove":
        return np.array([0.38, 0.62, COUNTER_TOP + 0.01])
    if frame in DRAWERS:
        return np.array([0.0, FRONT_Y - drawers[frame], DRAWER_FLOOR[frame]])
    if frame == CABINET:
        return CABINET_CENTRE.copy()
    raise KeyError(frame)


def regions(cabinet: bool = False) -> dict[str, Region]:
    """Where objects may rest in each frame (frame coordinates; z added per object).  With the
    cabinet the counter is the strip between the cabinet and the stove (the hard problems)."""
    out = {
        "counter": Region("counter", (-0.45, 0.55), (0.15, 0.78)),
        "stove": Region("stove", (-0.04, -0.04), (0.04, 0.04)),
        "top": Region("top", (-0.15, 0.04), (0.15, 0.21)),
        "bottom": Region("bottom", (-0.15, 0.04), (0.15, 0.21)),
    }
    if cabinet:
        out["counter"] = Region("counter", *HARD_COUNTER)
        hx, hy = CABINET_HALF
        out[CABINET] = Region(CABINET, (-hx + 0.01, -hy + 0.01), (hx - 0.01, hy - 0.01))
    return out


def cabinet_boxes(state: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """The cabinet's walls and lid as (centre, half extents) in the world, the lid slid ``state`` m left."""
    cx, cy, z0 = CABINET_CENTRE
    hx, hy = CABINET_HALF
    h, t = CABINET_WALL / 2, 0.01
    walls = [
        (np.array([cx, cy - hy - t, z0 + h]), np.array([hx + 2 * t, t, h])),  # front
        (np.array([cx, cy + hy + t, z0 + h]), np.array([hx + 2 * t, t, h])),  # back
        (np.array([cx - hx - t, cy, z0 + h]), np.array([t, hy, h])),  # left
        (np.array([cx + hx + t, cy, z0 + h]), np.array([t, hy, h])),  # right
    ]
    lid = (np.array([cx - state, cy, z0 + CABINET_WALL + 0.006]), np.array([hx + 2 * t, hy + 2 * t, 0.005]))
    return [*walls, lid]


def cabinet_handle(state: float) -> np.ndarray:
    """Where the gripper takes the lid: above its right edge."""
    cx, cy, z0 = CABINET_CENTRE
    out: np.ndarray = np.array([cx - state + CABINET_HALF[0] - 0.02, cy - 0.05, z0 + CABINET_WALL + 0.08])
    return out


BUTTON = np.array([0.38, 0.50, COUNTER_TOP + 0.015])


@dataclass
class Scene:
    """Body ids in one PyBullet client."""

    client: int
    robot: int
    drawers: int  # one multibody, link 0 = top tray, link 1 = bottom tray
    statics: tuple[int, ...]
    objects: dict[str, int]
    lid: int = -1  # the cabinet's lid (a multibody whose link 0 slides along -x), -1 without a cabinet
    # disconnects the client when the scene is closed or no longer referenced (set by build)
    release: weakref.finalize[[int], Scene] | None = field(default=None, repr=False, compare=False)

    @property
    def p(self) -> Any:
        return pybullet()


def _box(p: Any, c: int, half: tuple[float, float, float], pos: tuple[float, float, float],
         rgba: tuple[float, float, float, float], mass: float = 0.0) -> int:
    col = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=c)
    vis = p.createVisualShape(p.GEOM_BOX, halfExtents=half, rgbaColor=rgba, physicsClientId=c)
    return int(p.createMultiBody(mass, col, vis, pos, physicsClientId=c))


def _cabinet(p: Any, c: int, statics: list[int]) -> int:
    """The cabinet's walls (static boxes) and its lid on a prismatic joint; returns the lid's body."""
    colour = (0.45, 0.35, 0.5, 1)
    boxes = cabinet_boxes(0.0)
    for centre, half in boxes[:-1]:
        # before the pedestal, which stays last (the robot stands on it: collision checks skip it)
        h3 = (float(half[0]), float(half[1]), float(half[2]))
        c3 = (float(centre[0]), float(centre[1]), float(centre[2]))
        statics.insert(len(statics) - 1, _box(p, c, h3, c3, colour))
    centre, half = boxes[-1]
    col = p.createCollisionShape(p.GEOM_BOX, halfExtents=tuple(half), physicsClientId=c)
    vis = p.createVisualShape(p.GEOM_BOX, halfExtents=tuple(half), rgbaColor=(0.6, 0.5, 0.65, 1), physicsClientId=c)
    anchor = p.createCollisionShape(p.GEOM_SPHERE, radius=0.001, physicsClientId=c)
    return int(p.createMultiBody(
        0, anchor, -1, (0, 0, 0), linkMasses=[0.0], linkCollisionShapeIndices=[col], linkVisualShapeIndices=[vis],
        linkPositions=[tuple(float(v) for v in centre)], linkOrientations=[(0, 0, 0, 1)],
        linkInertialFramePositions=[(0, 0, 0)], linkInertialFrameOrientations=[(0, 0, 0, 1)],
        linkParentIndices=[0], linkJointTypes=[p.JOINT_PRISMATIC], linkJointAxis=[(-1, 0, 0)], physicsClientId=c))


def build(objects: tuple[str, ...] = ("green", "sugar", "cracker"), cabinet: bool = False) -> Scene:
    p = pybullet()
    pd = require("pybullet_data", "kitchen")
    c = p.connect(p.DIRECT)
    p.setAdditionalSearchPath(pd.getDataPath(), physicsClientId=c)
    wood, grey = (0.6, 0.45, 0.3, 1), (0.5, 0.5, 0.55, 1)
    statics = [
        _box(p, c, (0.7, 0.6, 0.005), (0.0, 0.3, -0.005), (0.8, 0.8, 0.8, 1)),  # floor
        _box(p, c, (0.175, 0.275, COUNTER_TOP / 2), (-0.425, 0.725, COUNTER_TOP / 2), wood),  # left block
        _box(p, c, (0.175, 0.275, COUNTER_TOP / 2), (0.425, 0.725, COUNTER_TOP / 2), wood),  # right block
        _box(p, c, (0.25, 0.275, 0.02), (0.0, 0.725, COUNTER_TOP - 0.02), wood),  # top slab
        _box(p, c, (0.25, 0.275, 0.01), (0.0, 0.725, 0.35), wood),  # divider
        _box(p, c, (0.25, 0.275, 0.06), (0.0, 0.725, 0.06), wood),  # plinth
        _box(p, c, (0.25, 0.01, COUNTER_TOP / 2), (0.0, 0.99, COUNTER_TOP / 2), wood),  # back
        _box(p, c, (0.07, 0.07, 0.005), (0.38, 0.62, COUNTER_TOP + 0.005), (0.2, 0.2, 0.2, 1)),  # stove
        _box(p, c, (0.015, 0.015, 0.015), tuple(BUTTON), (0.9, 0.1, 0.1, 1)),  # button
        _box(p, c, (0.12, 0.12, BASE_Z / 2 - 0.005), (0.0, -0.05, BASE_Z / 2 - 0.005), grey),  # pedestal
    ]
    # drawers: two trays on prismatic joints along -y, as links of one multibody
    tray_col = p.createCollisionShape(
        p.GEOM_BOX, halfExtents=(0.2, 0.125, 0.01), physicsClientId=c,
    )
    front_col = p.createCollisionShape(p.GEOM_BOX, halfExtents=(0.22, 0.01, 0.12), physicsClientId=c)
    tray_vis = p.createVisualShape(p.GEOM_BOX, halfExtents=(0.2, 0.125, 0.01),
                                   rgbaColor=(0.75, 0.6, 0.4, 1), physicsClientId=c)
    front_vis = p.createVisualShape(p.GEOM_BOX, halfExtents=(0.22, 0.01, 0.12),
                                    rgbaColor=(0.55, 0.4, 0.25, 1), physicsClientId=c)
    anchor = p.createCollisionShape(p.GEOM_SPHERE, radius=0.001, physicsClientId=c)
    links_col, links_vis, pos = [], [], []
    for d in DRAWERS:
        links_col += [tray_col, front_col]
        links_vis += [tray_vis, front_vis]
        z = DRAWER_FLOOR[d] - 0.01
        pos += [(0.0, FRONT_Y + 0.125, z), (0.0, FRONT_Y - 0.01, z + 0.08)]
    n = len(links_col)
    drawers = p.createMultiBody(
        0, anchor, -1, (0, 0, 0),
        linkMasses=[0.0] * n, linkCollisionShapeIndices=links_col, linkVisualShapeIndices=links_vis,
        linkPositions=[pos[0], (0, -0.135, 0.09), pos[2], (0, -0.135, 0.09)],
        linkOrientations=[(0, 0, 0, 1)] * n, linkInertialFramePositions=[(0, 0, 0)] * n,
        linkInertialFrameOrientations=[(0, 0, 0, 1)] * n,
        linkParentIndices=[0, 1, 0, 3],
        linkJointTypes=[p.JOINT_PRISMATIC, p.JOINT_FIXED, p.JOINT_PRISMATIC, p.JOINT_FIXED],
        linkJointAxis=[(0, -1, 0)] * n, physicsClientId=c,
    )
    robot = p.loadURDF("franka_panda/panda.urdf", (0.0, 0.0, BASE_Z), useFixedBase=True, physicsClientId=c)
    objs: dict[str, int] = {}
    for o in objects:
        objs[o] = _box(p, c, SIZES[o], (0.0, 0.0, -1.0 - len(objs)), COLOURS[o])
    lid = _cabinet(p, c, statics) if cabinet else -1
    sc = Scene(c, int(robot), int(drawers), tuple(statics), objs, lid)
    # each client holds its own copy of the meshes (~85 MB): an episode dropped without close()
    # (a run, a sweep's worker, a test) gives its client back when the scene is collected
    sc.release = weakref.finalize(sc, _disconnect, c)
    set_conf(sc, HOME)
    return sc


def close(sc: Scene) -> None:
    """Disconnect the scene's PyBullet client (each holds its own copy of the meshes)."""
    if sc.release is not None:
        sc.release()  # a finalizer runs once: a later collection does nothing
    else:
        _disconnect(sc.client)


def _disconnect(client: int) -> None:
    try:
        pybullet().disconnect(physicsClientId=client)
    except Exception:  # noqa: BLE001 - already disconnected
        pass


def set_conf(sc: Scene, q: tuple[float, ...]) -> None:
    p = sc.p
    p.resetBasePositionAndOrientation(sc.robot, (q[0], 0.0, BASE_Z), (0, 0, 0, 1), physicsClientId=sc.client)
    for j, v in zip(ARM_JOINTS, q[1:], strict=True):
        p.resetJointState(sc.robot, j, v, physicsClientId=sc.client)
    for j in (9, 10):
        p.resetJointState(sc.robot, j, 0.04, physicsClientId=sc.client)


def set_drawer(sc: Scene, drawer: str, q: float) -> None:
    """Set a container's joint: a drawer's travel, or how far the cabinet's lid has slid."""
    if drawer == CABINET:
        if sc.lid >= 0:
            sc.p.resetJointState(sc.lid, 0, q, physicsClientId=sc.client)
        return
    link = 0 if drawer == "top" else 2
    sc.p.resetJointState(sc.drawers, link, q, physicsClientId=sc.client)


def set_object(sc: Scene, name: str, world: np.ndarray) -> None:
    sc.p.resetBasePositionAndOrientation(sc.objects[name], tuple(float(v) for v in world), (0, 0, 0, 1),
                                         physicsClientId=sc.client)


def ee_position(sc: Scene) -> np.ndarray:
    st = sc.p.getLinkState(sc.robot, EE_LINK, computeForwardKinematics=True, physicsClientId=sc.client)
    return np.array(st[4])


def camera_matrices(sc: Scene, width: int = 320, height: int = 240) -> tuple[Any, Any]:
    p = sc.p
    view = p.computeViewMatrix(tuple(CAMERA), tuple(CAMERA_TARGET), (0, 0, 1), physicsClientId=sc.client)
    proj = p.computeProjectionMatrixFOV(60, width / height, 0.05, 5.0, physicsClientId=sc.client)
    return view, proj

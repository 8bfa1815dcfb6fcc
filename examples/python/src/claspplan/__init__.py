"""claspplan from Python: robots, virtual linking, an object's loops from NumPy arrays, and clasp
planning on scenario files, with the command line's rules and reasons.

Units are SI (metres, radians); frames follow REP 103 (world: x forward, y left, z up; a camera's
pose is its optical frame: z forward, x right, y down). Malformed input raises InputError (a
ValueError) with the one-line reason `claspplan` prints. Long calls release the GIL: run them in a
thread to keep an interpreter responsive; bound them with `time_limit` or `max_cycles`.
"""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import _claspplan
from ._claspplan import InputError, Robot

__all__ = [
    "InputError",
    "Robot",
    "linking_number",
    "gauss_linking",
    "virtual_linking",
    "perceive",
    "plan",
    "read_depth",
    "read_cloud",
    "run",
    "verify",
]

ArrayLike = Union[np.ndarray, Sequence[Sequence[float]]]
DepthInput = Tuple[ArrayLike, ArrayLike, ArrayLike]


def _points(a: ArrayLike, what: str) -> np.ndarray:
    p = np.ascontiguousarray(a, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3:
        raise InputError(f"{what}: expected an (n, 3) array, got shape {p.shape}")
    return p


def _cloud_list(points: Any) -> list:
    """One (n, 3) cloud, or a list of them, as a list."""
    if isinstance(points, np.ndarray):
        return [points]
    first = np.asarray(points[0]) if len(points) else None
    return list(points) if first is not None and first.ndim == 2 else [points]


def linking_number(a: ArrayLike, b: ArrayLike) -> int:
    """Lk of two closed polylines (n x 3 each; the last point joins the first): exact, signed by
    the right-hand rule (paper eq. 1)."""
    return _claspplan.linking_number(_points(a, "a"), _points(b, "b"))


def gauss_linking(a: ArrayLike, b: ArrayLike, a_closed: bool = True, b_closed: bool = True) -> float:
    """The Gauss linking integral of two polylines, each closed or open (paper eq. 1)."""
    return _claspplan.gauss_linking(_points(a, "a"), a_closed, _points(b, "b"), b_closed)


def virtual_linking(loop: ArrayLike, finger: ArrayLike) -> float:
    """VLk of a closed loop and an open finger curve closed by its virtual cord (paper eq. 2)."""
    return _claspplan.virtual_linking(_points(loop, "loop"), _points(finger, "finger"))


def perceive(
    depth: Sequence[DepthInput] = (),
    points: Optional[Union[ArrayLike, Sequence[ArrayLike]]] = None,
    sensor_origin: Optional[Union[ArrayLike, Sequence[Optional[ArrayLike]]]] = None,
    robot: Optional[Union[str, Robot]] = None,
    crop: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    n_points: int = 2000,
    d: float = 0.0,
    seed: int = 1,
    no_reading_is_free: bool = False,
) -> Dict[str, Any]:
    """The object's loops (paper Sec. IV-A) with their verdicts, as `claspplan loops` ranks them.

    depth: (depth, K, T_world_camera) per view: an (h, w) array of metres (0 or NaN: no reading),
        the 3 x 3 intrinsics and the camera's 4 x 4 pose in the world.
    points: an (n, 3) cloud in the world frame, or a list of them; sensor_origin: each cloud's
        sensor position (3,), or None. A cloud without one cannot tell a hole from an unseen gap:
        its loops are not claspable (the reason says so).
    robot: rank the loops for this robot's hand (a built-in name or description file).
    crop: (min, max) corners of the workspace box for the points.
    n_points: N, the points K_d is built on; d: its edge bound in metres (0: automatic).
    no_reading_is_free: a pixel without a reading saw nothing up to any range (a rendering of a
        complete scene); a real sensor's missing readings leave their rays unknown (the default).

    Returns a dict: beta1, d, cloud (N x 3), input_points, loops (best first: points, rank,
    claspable, verdict, reason, length, hole_width, centre, normal), targets (k x 3) and
    target_tangents (k x 3) on the best claspable loop.
    """
    views, clouds, box = _object_arrays(depth, points, sensor_origin, crop)
    name = robot.source if isinstance(robot, Robot) else (robot or "")
    return _claspplan.perceive(views, clouds, name, box, int(n_points), float(d), int(seed),
                               bool(no_reading_is_free))


def _object_arrays(depth, points, sensor_origin, crop):
    """perceive()'s and plan()'s object arguments as the C++ module takes them."""
    clouds = []
    if points is not None:
        arrays = _cloud_list(points)
        if sensor_origin is None:
            origins = [None] * len(arrays)
        elif len(arrays) == 1:
            origins = [sensor_origin]
        else:
            origins = list(sensor_origin)
        if len(origins) != len(arrays):
            raise InputError("sensor_origin: one per cloud (or None)")
        for a, o in zip(arrays, origins):
            clouds.append((_points(a, "points"),
                           None if o is None else np.asarray(o, dtype=np.float64).reshape(3)))
    views = [(np.asarray(d, dtype=np.float32), np.asarray(k, dtype=np.float64).reshape(3, 3),
              np.asarray(t, dtype=np.float64).reshape(4, 4)) for d, k, t in depth]
    box = None
    if crop is not None:
        box = np.concatenate([np.asarray(crop[0], dtype=np.float64).reshape(3),
                              np.asarray(crop[1], dtype=np.float64).reshape(3)])
    return views, clouds, box


def plan(
    robot: Union[str, Robot],
    start: ArrayLike,
    depth: Sequence[DepthInput] = (),
    points: Optional[Union[ArrayLike, Sequence[ArrayLike]]] = None,
    sensor_origin: Optional[Union[ArrayLike, Sequence[Optional[ArrayLike]]]] = None,
    environment: Sequence[Tuple[ArrayLike, ArrayLike]] = (),
    crop: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    n_points: int = 2000,
    d: float = 0.0,
    targets: int = 12,
    near: Optional[ArrayLike] = None,
    goal_linking: Optional[float] = None,
    pre_expansions: Optional[int] = None,
    random_probability: Optional[float] = None,
    seed: int = 1,
    max_cycles: Optional[int] = None,
    time_limit: Optional[float] = None,
    no_reading_is_free: bool = False,
    controller_only: bool = False,
) -> Dict[str, Any]:
    """Plans a clasp (paper Alg. 1: TS-RRT, the fingers closed and the clasp verified at each goal)
    from arrays: perception as in perceive(), then the search from `start` (the arm's joints, or
    all joints).

    environment: (size, centre) boxes the robot must avoid (the floor, a table), metres.
    targets: clasp targets on the loop; near: clasp the claspable loop nearest this point;
    goal_linking: the virtual-linking goal (default: the robot's); pre_expansions,
    random_probability: the planner's n and P (paper Sec. V); seed, max_cycles, time_limit as for
    `claspplan run`. controller_only: the clasp controller alone from `start` toward the nearest
    clasp target, no search (`claspplan run --controller-only`); path is then its steps.

    Returns a dict: status ("success", "no_claspable_loop", "no_clasp"), verified, reason, path
    (M x dof), final_q, start, loop (k x 3), targets (t x 3), target, virtual_linking,
    verification (the secure-clasp check's stages, as result.json has them), object (as
    perceive() returns it), timings (seconds per phase), cycles and nodes.
    """
    model = robot if isinstance(robot, Robot) else Robot(robot)
    views, clouds, box = _object_arrays(depth, points, sensor_origin, crop)
    boxes = [(np.asarray(size, dtype=np.float64).reshape(3),
              np.asarray(centre, dtype=np.float64).reshape(3)) for size, centre in environment]
    result = _claspplan.plan(
        model, np.asarray(start, dtype=np.float64).reshape(-1), views, clouds, boxes, box,
        int(n_points), float(d), int(targets),
        None if near is None else np.asarray(near, dtype=np.float64).reshape(3), goal_linking,
        pre_expansions, random_probability, int(seed), max_cycles, time_limit,
        bool(no_reading_is_free), bool(controller_only))
    result["verification"] = json.loads(result["verification"])
    return result


def read_depth(png: str, camera: str) -> Tuple[np.ndarray, np.ndarray, np.ndarray, bool]:
    """A 16-bit depth PNG and its camera file (claspplan's formats) as perceive() takes them:
    (depth in metres (h, w), K (3, 3), T_world_camera (4, 4), no_reading_is_free)."""
    return _claspplan.read_depth(os.fspath(png), os.fspath(camera))


def read_cloud(path: str) -> Dict[str, Any]:
    """A .pcd, .ply or .xyz cloud: points (n, 3; an organized PCD keeps its grid, NaN where the
    sensor had no reading), width, height, and viewpoint (the PCD VIEWPOINT as a 4 x 4 pose, or
    None)."""
    points, width, height, viewpoint = _claspplan.read_cloud(os.fspath(path))
    return {"points": points, "width": width, "height": height, "viewpoint": viewpoint}


def run(
    scenario: str,
    seed: Optional[int] = None,
    max_cycles: Optional[int] = None,
    time_limit: Optional[float] = None,
    robot: Optional[Union[str, Robot]] = None,
    out_dir: Optional[str] = None,
    pictures: bool = False,
    controller_only: bool = False,
    next_views: int = 0,
) -> Dict[str, Any]:
    """Plans a clasp for a scenario file as `claspplan run SCENARIO --json` does, with the same
    result for the same inputs and seed; controller_only as `--controller-only`, next_views as
    `--next-views` (0 to 10).

    Returns `run --json`'s summary with, added: exit_code (0 a verified clasp, 1 none), result
    (result.json), path (M x dof joint waypoints, start to the closed hand), final_q (dof,) and
    loop (k x 3, the clasped loop) as arrays, and out_dir. Without out_dir the files are written
    to a temporary folder that is removed.
    """
    name = robot.source if isinstance(robot, Robot) else (robot or "")
    with tempfile.TemporaryDirectory(prefix="claspplan-") as tmp:
        out = out_dir or tmp
        code, text = _claspplan.run_file(os.fspath(scenario), seed, max_cycles, time_limit, name,
                                         out, pictures, controller_only, next_views)
        summary = json.loads(text)
        with open(os.path.join(out, "result.json"), encoding="utf-8") as f:
            result = json.load(f)
    summary["exit_code"] = code
    summary["result"] = result
    summary["path"] = np.asarray(result.get("waypoints", []), dtype=np.float64)
    summary["final_q"] = np.asarray(result.get("final_q", []), dtype=np.float64)
    loop = result.get("loop") or []
    summary["loop"] = np.asarray(loop.get("points", []) if isinstance(loop, dict) else loop,
                                 dtype=np.float64).reshape(-1, 3)
    summary["out_dir"] = out_dir
    return summary


def verify(result: str, seed: Optional[int] = None) -> Dict[str, Any]:
    """The secure-clasp check of a saved result.json again (`claspplan verify --json`): the
    paper's random motions and the escape searches; `secure` is True when no stage freed the
    object. The seed defaults to the result's."""
    return json.loads(_claspplan.verify_file(os.fspath(result), seed))

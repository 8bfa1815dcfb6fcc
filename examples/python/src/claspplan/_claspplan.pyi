# Type stubs of claspplan's C++ module (claspplan_module.cpp); the package `claspplan` wraps it.
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

class InputError(ValueError):
    """Malformed input: the one-line reason the command line prints."""

class Robot:
    """A robot: a built-in name (kr5_sdh, kr5_dlr, kr5_icub, kr5_armar3) or a hand-description
    file. Immutable; q is arm joints then hand joints, radians (metres for prismatic joints)."""

    def __init__(self, name: str) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def arm_dof(self) -> int: ...
    @property
    def hand_dof(self) -> int: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def lower(self) -> np.ndarray: ...
    @property
    def upper(self) -> np.ndarray: ...
    @property
    def home(self) -> np.ndarray:
        """The arm's home with the hand's open pre-shape."""
    @property
    def vlink_goal(self) -> float: ...
    @property
    def warnings(self) -> List[str]: ...
    def forward_kinematics(self, q: np.ndarray) -> Dict[str, np.ndarray]:
        """Every link's 4 x 4 pose in the world at q."""
    def finger_curves(self, q: np.ndarray) -> List[np.ndarray]:
        """The finger curves (paper Sec. IV-B) at q, one (k x 3) array each."""
    def self_collisions(self, q: np.ndarray) -> List[Tuple[str, str]]:
        """Every pair of links in contact at q."""
    def hand_size(self) -> Dict[str, object]:
        """finger_thickness, closed_aperture (m) and closed_q (the hand's joints)."""

def linking_number(a: np.ndarray, b: np.ndarray) -> int: ...
def gauss_linking(a: np.ndarray, a_closed: bool, b: np.ndarray, b_closed: bool) -> float: ...
def virtual_linking(loop: np.ndarray, finger: np.ndarray) -> float: ...
def perceive(
    depth: Sequence[Tuple[np.ndarray, np.ndarray, np.ndarray]],
    clouds: Sequence[Tuple[np.ndarray, Optional[np.ndarray]]],
    robot: str,
    crop: Optional[np.ndarray],
    points: int,
    d: float,
    seed: int,
    no_reading_is_free: bool,
) -> Dict[str, object]: ...
def plan(
    robot: Robot,
    start: np.ndarray,
    depth: Sequence[Tuple[np.ndarray, np.ndarray, np.ndarray]],
    clouds: Sequence[Tuple[np.ndarray, Optional[np.ndarray]]],
    boxes: Sequence[Tuple[np.ndarray, np.ndarray]],
    crop: Optional[np.ndarray],
    points: int,
    d: float,
    targets: int,
    near: Optional[np.ndarray],
    goal_linking: Optional[float],
    pre_expansions: Optional[int],
    random_probability: Optional[float],
    seed: int,
    max_cycles: Optional[int],
    time_limit: Optional[float],
    no_reading_is_free: bool,
    controller_only: bool,
) -> Dict[str, object]: ...
def verify_file(path: str, seed: Optional[int]) -> str: ...
def read_depth(png: str, camera: str) -> Tuple[np.ndarray, np.ndarray, np.ndarray, bool]: ...
def read_cloud(path: str) -> Tuple[np.ndarray, int, int, Optional[np.ndarray]]: ...
def run_file(
    path: str,
    seed: Optional[int],
    max_cycles: Optional[int],
    time_limit: Optional[float],
    robot: str,
    out: str,
    pictures: bool,
    controller_only: bool,
    next_views: int,
) -> Tuple[int, str]: ...

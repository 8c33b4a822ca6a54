"""Numbers the NAMO agent and world share: sensor, noise, tolerances and costs."""

from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist


@dataclass(frozen=True)
class Sensor:
    range: float = 4.0  # metres
    fov: float = math.radians(160.0)  # radians
    sigma0: float = 0.01  # object position noise at 0 m (m)
    sigma_per_m: float = 0.015  # growth of the noise per metre of distance
    landmark_range: float = 6.0
    landmark_sigma: float = 0.03
    miss_prob: float = 0.0  # chance a visible object goes undetected on one look
    near_range: float = 1.2  # a short-range all-round sensor (a base laser) runs after every action

    def sigma_at(self, d: float) -> float:
        return self.sigma0 + self.sigma_per_m * d


@dataclass(frozen=True)
class Noise:
    """What goes wrong in the world (the agent's model knows the rates only through its tolerances)."""

    motion_per_m: float = 0.01  # std of the end-point error per metre driven
    move_fail: float = 0.0  # a move stops early with this probability
    grasp_fail: float = 0.0  # a grasp misses with this probability
    grasp_tol: float = 0.15  # a grasp misses when the object is further than this from where expected
    place_sigma: float = 0.01  # placement error


@dataclass(frozen=True)
class Params:
    """The agent's model: tolerances, costs and the motion planner's settings."""

    segment: float = 1.6  # longest straight move (m); a path is split into moves this long
    clear_cost: float = 5.0  # path-planning cost of going through a known movable obstacle
    look_cost: float = 1.0  # path-planning cost of entering a shadow without foresight
    shadow_cost: float = 3.0  # foresight: cost of entering an object's epsilon-shadow (scaled by its size)
    eps_clear: float = 0.025  # BClear tolerance (probability that a region is not clear)
    eps_pick: float = 0.06  # BVRelPose needed before picking (m)
    eps_loc: float = 0.2  # robot localisation needed before a base move (m)
    at_tol: float = 0.15  # RobotAt tolerance (m)
    # RobotAt(p) away from the robot's nominal pose needs the mean this many standard deviations of
    # the pose estimate inside at_tol (belief.surely_at): a move stopped just inside the tolerance is
    # not taken for arrival when the truth may lie just outside it
    at_sd: float = 2.0
    refit: float = 0.15  # Fits: a manipulation is planned again once the object's estimate moved this far (m)
    fog_observed_slack: int = 3  # Observed: this many visible fog cells are tolerated
    connectivity: bool = True  # placements keep the robot connected to where it started (Fig. 8)
    taboo_cost: float = 50.0  # foresight: placement penalty for meeting a region a plan needs clear
    fog_place_cost: float = 4.0  # placement penalty for putting an object down partly in fog
    motion_model: float = 0.01  # the agent's model of its odometry noise per metre
    reconsider_gain: float = 1.0  # selective: replan when a path this much shorter exists (m)
    # selective: ... and by this many standard deviations of the fog cost the new path runs into and
    # the planned one does not (fogcost.fog_cost_spread; 2.33: one-sided 99 %); 0: the fixed gain alone
    reconsider_sd: float = 2.33
    # fog is priced by its expected clearance cost (fogcost.py): a Gamma prior on the density of
    # objects in free space (this many objects in this many m^2), updated by what the robot observed
    fog_pricing: bool = True
    fog_prior_objects: float = 1.0
    fog_prior_area: float = 10.0  # m^2
    fog_prior_width: float = 0.5  # m: the mean object width assumed before any object is seen
    pass_margin: float = 0.1  # m: beyond the robot's diameter, the gap it needs to pass an object met in fog

    @property
    def k_clear(self) -> float:
        """Standard deviations of an object's pose that make its epsilon-shadow."""
        return NormalDist().inv_cdf(1.0 - self.eps_clear)


DEFAULT_PARAMS = Params()
DEFAULT_SENSOR = Sensor()
DEFAULT_NOISE = Noise()

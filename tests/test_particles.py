"""The particle filter's Bayesian update against hand-computed cases."""

from __future__ import annotations

import math

import numpy as np
import pytest

from nowplan.belief.particles import PoseParticles, Region, SensorModel, gaussian_density
from nowplan.errors import ModelError

ORIGINS = {"a": np.zeros(3), "b": np.array([1.0, 0.0, 0.0])}


def two_particles() -> PoseParticles:
    return PoseParticles(np.array(["a", "b"], dtype=object), np.zeros((2, 3)))


def vis_only_first(frames: np.ndarray, world: np.ndarray) -> np.ndarray:
    return np.array([1.0 if f == "a" else 0.0 for f in frames])


def test_negative_evidence_hand_computed() -> None:
    pb = two_particles()
    sensor = SensorModel(p_fn=0.2, sigma=0.01)
    pb.update(sensor, vis_only_first, ORIGINS, None, np.random.default_rng(0))
    # visible particle: 0.5 * 0.2; hidden one: 0.5 * 1  ->  0.1 / 0.6
    assert pb.frame_mass("a") == pytest.approx(0.1 / 0.6)
    assert pb.frame_mass("b") == pytest.approx(0.5 / 0.6)


def test_partial_visibility_miss() -> None:
    pb = two_particles()
    sensor = SensorModel(p_fn=0.1, sigma=0.01)
    vis = lambda f, w: np.array([0.5, 1.0])  # noqa: E731
    pb.reweight(1.0 - vis(None, None) * (1 - sensor.p_fn))
    a, b = 1 - 0.5 * 0.9, 1 - 0.9
    assert pb.weights[0] == pytest.approx(a / (a + b))


def test_detection_hand_computed() -> None:
    frames = np.array(["a", "a"], dtype=object)
    pb = PoseParticles(frames, np.array([[0.0, 0, 0], [0.02, 0, 0]]), np.array([0.3, 0.7]))
    sensor = SensorModel(p_fn=0.1, sigma=0.01)
    z = np.array([0.0, 0.0, 0.0])
    ones = lambda f, w: np.ones(len(f))  # noqa: E731
    pb.update(sensor, ones, ORIGINS, z, np.random.default_rng(0))
    l0 = 0.3 * math.exp(0.0)
    l1 = 0.7 * math.exp(-0.5 * (0.02 / 0.01) ** 2)
    # ESS stays above n/2? if not, resampling changes weights; check before resampling instead
    pb2 = PoseParticles(frames, np.array([[0.0, 0, 0], [0.02, 0, 0]]), np.array([0.3, 0.7]))
    world = pb2.world(ORIGINS)
    pb2.reweight(0.9 * gaussian_density(z, world, 0.01))
    assert pb2.weights[0] == pytest.approx(l0 / (l0 + l1))
    assert len(pb) == 2


def test_detection_concentrates_uniform_prior() -> None:
    rng = np.random.default_rng(3)
    region = Region("a", (0.0, 0.0), (0.4, 0.4))
    pb = PoseParticles.uniform([region], 100, rng)
    z = np.array([0.2, 0.2, 0.0])
    ones = lambda f, w: np.ones(len(f))  # noqa: E731
    sensor = SensorModel(p_fn=0.1, sigma=0.02)
    before = pb.mass_near("a", z, 0.05)
    pb.update(sensor, ones, ORIGINS, z, rng, supports={"a": region})
    assert pb.mass_near("a", z, 0.05) > before
    assert pb.mass_near("a", z, 0.05) > 0.8


def test_far_detection_reseeds() -> None:
    pb = PoseParticles.point("a", (0.0, 0.0, 0.0), 10)
    z = np.array([0.5, 0.5, 0.0])
    ones = lambda f, w: np.ones(len(f))  # noqa: E731
    pb.update(SensorModel(0.1, 0.01), ones, ORIGINS, z, np.random.default_rng(1), z_frame="a")
    assert pb.mass_near("a", z, 0.05) == pytest.approx(1.0)


def test_uniform_prior_respects_areas_and_bad_inputs() -> None:
    rng = np.random.default_rng(0)
    big, small = Region("a", (0, 0), (0.9, 1.0)), Region("b", (0, 0), (0.1, 1.0))
    pb = PoseParticles.uniform([big, small], 2000, rng)
    assert pb.frame_mass("a") == pytest.approx(0.9, abs=0.03)
    assert all(big.contains(pb.poses[pb.frames == "a"][:, :2]))
    with pytest.raises(ModelError):
        SensorModel(p_fn=1.0)
    with pytest.raises(ModelError):
        PoseParticles.uniform([], 10, rng)


def test_resample_is_seeded() -> None:
    def run(seed: int) -> np.ndarray:
        pb = PoseParticles.uniform([Region("a", (0, 0), (1, 1))], 50, np.random.default_rng(0))
        pb.weights = np.linspace(1, 2, 50) / np.linspace(1, 2, 50).sum()
        pb.resample(np.random.default_rng(seed), jitter=0.01)
        return pb.poses

    assert np.array_equal(run(5), run(5))
    assert not np.array_equal(run(5), run(6))


@pytest.mark.parametrize("sigma", [0.01, 0.03, 0.05])
def test_repeated_detections_localise_a_noisy_sensor(sigma: float) -> None:
    """Detections with noise σ, each a fresh draw around the true pose, concentrate the cloud within
    2 cm (the kitchen's ``localized`` test: 90 % of the mass) within a bounded number of looks.  With the
    resampling jitter at σ/2 whatever the cloud's spread, σ = 0.03 m never got there (a floor of about
    0.024 m per axis: the kitchen planned a look again and again)."""
    rng = np.random.default_rng(7)
    region = Region("a", (0.0, 0.0), (0.4, 0.4))
    pb = PoseParticles.uniform([region], 100, rng)
    truth = np.array([0.2, 0.2, 0.0])
    ones = lambda f, w: np.ones(len(f))  # noqa: E731
    sensor = SensorModel(p_fn=0.1, sigma=sigma)
    looks = None
    for k in range(1, 101):
        z = truth + np.append(rng.normal(0.0, sigma, 2), 0.0)
        pb.update(sensor, ones, ORIGINS, z, rng, supports={"a": region})
        assert pb.roughening(sensor) <= sigma / 2 + 1e-12
        if pb.mass_near("a", truth, 0.02) >= 0.9:
            looks = k
            break
    # the Kalman bound: (σ / 0.0093)² looks take a Gaussian's spread to 90 % within 2 cm
    assert looks is not None and looks <= 4 * max(1.0, (sigma / 0.0093) ** 2), looks


def test_roughening_follows_the_clouds_spread() -> None:
    sensor = SensorModel(p_fn=0.1, sigma=0.03)
    rng = np.random.default_rng(1)
    wide = PoseParticles.uniform([Region("a", (0.0, 0.0), (0.4, 0.4))], 100, rng)
    tight = PoseParticles.uniform([Region("a", (0.2, 0.2), (0.205, 0.205))], 100, rng)
    assert 0.005 < wide.roughening(sensor) <= 0.015  # a wide prior: about as before (the sensor's σ/2)
    assert tight.roughening(sensor) < 0.001  # a small fraction of the cloud's own spread
    both = PoseParticles(np.array(["a", "b"], dtype=object), np.zeros((2, 3)))
    assert both.roughening(sensor) == pytest.approx(0.015)  # frames not comparable: the bound

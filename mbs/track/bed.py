"""A ballasted track under each wheel: rail, sleeper and ballast masses on the rail pad, the ballast
and the subgrade, lumped from the continuous track by the Rayleigh-Ritz method.

The vehicle-track models that reproduce wheel-flat impacts (Nielsen, Wear 265 (2008) 1465-1471;
Zhai, *Vehicle-Track Coupled Dynamics*, Springer 2020) put the rail on discrete pads over sleepers
and ballast; on rigid rails the wheelset rings undamped on its Hertz springs (near 200 Hz) and an
impact is several times too large.  Here each wheel carries its own track, moving with it:

* a rail of mass ``rail_mass`` per metre and bending stiffness ``rail_EI`` on rail seats
  ``sleeper_spacing`` a apart, each a pad ``(pad_k, pad_c)`` over half a sleeper
  (``sleeper_mass``), over a ballast block (``ballast_mass``) on the ballast spring
  ``(ballast_k, ballast_c)``, over the subgrade ``(subgrade_k, subgrade_c)`` - Zhai's three
  layers, per rail seat.  Defaults: Zhai, Wang and Lin, J. Sound Vib. 270 (2004) 673-683
  (ballasted track with 60 kg/m rail), taken as the open TTB-2D model tabulates them, not checked
  against the printed table (``assumed`` in the config);
* statically the support is a Winkler foundation of modulus ``k_f = k_s / a``, ``k_s`` the three
  springs in series, and a point load Q deflects the rail as ``w(x) = w0 exp(-beta |x|) (cos
  beta x + sin beta |x|)``, ``beta = (k_f / (4 EI))^(1/4)``, ``w0 = Q beta / (2 k_f)`` (Hetenyi,
  *Beams on Elastic Foundation*, 1946; Timoshenko, Trans. ASME 1927);
* each layer moves in that shape, scaled by its own coordinate (one Ritz function per layer).
  Its kinetic and strain energies then give the lumped model with ``L = int (w / w0)^2 dx =
  3 / (2 beta)``: masses ``m L / a`` of the sleepers and ballast and ``rail_mass L`` of the rail;
  the springs and dampers of the seats likewise ``k L / a``; the rail's bending, ``EI int
  (w'' / w0)^2 dx = 2 EI beta^3 = k_f / (2 beta)``, a spring from the rail to the far track
  (ground).  The static stiffness of the lumped chain, ``k_f / (2 beta) + k_s L / a``, is
  Hetenyi's ``2 k_f / beta`` exactly (:func:`static_stiffness`): the lumping keeps the track's
  static deflection under the wheel.

The one shape is the static one: at impact frequencies the rail decouples from the sleepers
over a shorter length (a lighter effective rail), and the sleepers' discreteness (passing
frequency ``V / a``) is left out.  Only the vertical contact force loads the track; it stays
rigid laterally and along the rail.
"""
from __future__ import annotations

from dataclasses import dataclass

from axlebox._params import check_ranges, param

MODELS = ("rigid", "ballasted")


@dataclass(frozen=True)
class Seats:
    """The ballasted track per rail seat (SI; declared here, once: the car config's ``[track]``
    takes these fields over).  Defaults: Zhai, Wang and Lin 2004, 60 kg/m rail (module
    docstring)."""

    rail_mass: float = param(60.64, 10.0, 200.0, "kg/m", "rail mass per metre, ballasted track (Zhai et al. "
                             "2004, 60 kg/m rail)")
    rail_EI: float = param(6.624e6, 1e5, 1e8, "N m^2", "rail bending stiffness, E 205.9 GPa, I 3217 cm^4 "
                           "(Zhai et al. 2004)")
    sleeper_spacing: float = param(0.6, 0.3, 1.5, "m", "rail seat (sleeper) spacing (Zhai et al. 2004)")
    pad_k: float = param(6.5e7, 1e6, 1e10, "N/m", "rail pad stiffness, per rail seat (Zhai et al. 2004)")
    pad_c: float = param(75000.0, 0.0, 1e7, "N s/m", "rail pad damping, per rail seat (Zhai et al. 2004)")
    sleeper_mass: float = param(125.5, 10.0, 2000.0, "kg", "half a sleeper, per rail seat (Zhai et al. 2004)")
    ballast_mass: float = param(531.4, 0.0, 5000.0, "kg", "the ballast block under a rail seat (Zhai et al. "
                                "2004)")
    ballast_k: float = param(1.3775e8, 1e6, 1e10, "N/m", "ballast stiffness, per rail seat (Zhai et al. "
                             "2004)")
    ballast_c: float = param(58800.0, 0.0, 1e7, "N s/m", "ballast damping, per rail seat (Zhai et al. 2004)")
    subgrade_k: float = param(7.75e7, 1e6, 1e10, "N/m", "subgrade stiffness, per rail seat (Zhai et al. "
                              "2004)")
    subgrade_c: float = param(31150.0, 0.0, 1e7, "N s/m", "subgrade damping, per rail seat (Zhai et al. "
                              "2004)")

    def __post_init__(self):
        check_ranges(self)


@dataclass(frozen=True)
class Lumped:
    """The lumped track under one wheel (SI): masses of the rail, sleeper and ballast layers; the
    pad (rail-sleeper), ballast (sleeper-ballast), subgrade (ballast-ground) springs and dampers;
    the rail's bending spring to the ground; ``beta`` (1/m) and the Ritz length ``L`` (m)."""

    m_rail: float
    m_sleeper: float
    m_ballast: float
    k_pad: float
    c_pad: float
    k_ballast: float
    c_ballast: float
    k_subgrade: float
    c_subgrade: float
    k_bend: float
    beta: float
    L: float


def _foundation(t: Seats) -> tuple[float, float]:
    """``(k_f, beta)``: the Winkler modulus of the seats (three springs in series over the
    spacing, N/m^2) and the rail's wavenumber on it (1/m)."""
    k_s = 1.0 / (1.0 / t.pad_k + 1.0 / t.ballast_k + 1.0 / t.subgrade_k)
    k_f = k_s / t.sleeper_spacing
    return k_f, (k_f / (4.0 * t.rail_EI)) ** 0.25


def lumped(t: Seats) -> Lumped:
    """The lumped track of the seats ``t`` (:class:`Seats`, or the car config's ``[track]``,
    which has their fields; module docstring)."""
    a = t.sleeper_spacing
    k_f, beta = _foundation(t)
    L = 3.0 / (2.0 * beta)
    s = L / a
    return Lumped(m_rail=t.rail_mass * L, m_sleeper=t.sleeper_mass * s,
                  m_ballast=t.ballast_mass * s, k_pad=t.pad_k * s, c_pad=t.pad_c * s,
                  k_ballast=t.ballast_k * s, c_ballast=t.ballast_c * s,
                  k_subgrade=t.subgrade_k * s, c_subgrade=t.subgrade_c * s,
                  k_bend=k_f / (2.0 * beta), beta=beta, L=L)


def static_stiffness(m: Lumped) -> float:
    """The lumped track's stiffness under the wheel (N/m): bending in parallel with the three
    seat springs in series."""
    return m.k_bend + 1.0 / (1.0 / m.k_pad + 1.0 / m.k_ballast + 1.0 / m.k_subgrade)


def winkler_stiffness(t: Seats) -> float:
    """Hetenyi's point stiffness ``2 k_f / beta`` of the continuous rail on its seats (N/m)."""
    k_f, beta = _foundation(t)
    return 2.0 * k_f / beta

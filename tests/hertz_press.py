"""Hertz's press of a paraboloid, for the press-to-force tests of both boundary-element methods:
the scene (E* = 1: E = 0.75, nu = 0.5), and Hertz's approach and contact radius at its force."""

import math

import contact_scene as cs

R, E_STAR, F0 = 1.0, 1.0, 0.05
SCENE = cs.Scene(
    cs.Indenter(cs.Circle(0.4), cs.Paraboloid(R)),
    cs.Homogeneous(0.75, 0.5),
    cs.Adhesion(0.0),
    cs.Loading(press_force=F0),
)
#: d = (9 F^2 / (16 R E*^2))^(1/3) and a = sqrt(R d)
APPROACH = (9 * F0**2 / (16 * R * E_STAR**2)) ** (1 / 3)
CONTACT_RADIUS = math.sqrt(R * APPROACH)

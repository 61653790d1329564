#!/usr/bin/env python3
"""Generalized-alpha (Arnold & Bruls form, as integrators/generalized_alpha.cpp) on a mass bouncing
under gravity on a one-sided spring with the tension-only rope's smoothed law (docs/model.md
"Tension-only rope"). Prints the largest energy over 20000 steps relative to the start for a
range of omega h: a Newmark-type scheme keeps a linear spring's energy bounded, not this one's.

Usage: /usr/bin/python3 scripts/one_sided_spring.py
"""

BAND = 1e-5  # kSlackBand, in units of the spring's own strain
GRAVITY = 0.05  # weight / (k * 1 length unit): the spring is compressed 0.05 at rest


def scheme(rho):
    am = (2.0 * rho - 1.0) / (rho + 1.0)
    af = rho / (rho + 1.0)
    gamma = 0.5 + af - am
    beta = 0.25 * (gamma + 0.5) ** 2
    return am, af, gamma, beta


def law(s):
    """Force and tangent of the unit spring at stretch s (ancfAxialLaw with EA = 1)."""
    if s >= BAND:
        return s, 1.0
    if s > -BAND:
        return (s + BAND) ** 2 / (4.0 * BAND), (s + BAND) / (2.0 * BAND)
    return 0.0, 0.0


def potential(s):
    if s >= BAND:
        return 0.5 * s * s + BAND * BAND / 6.0
    if s > -BAND:
        return (s + BAND) ** 3 / (12.0 * BAND)
    return 0.0


def energy(x, v):
    # The spring pushes the mass up where x < 0 (stretch -x); gravity pulls it down.
    return 0.5 * v * v + potential(-x) + GRAVITY * x


def largest_energy_ratio(omega_h, rho, steps=20000):
    am, af, gamma, beta = scheme(rho)
    h = omega_h  # unit mass and stiffness: omega = 1
    x, v = 0.0, -1.0
    acc = law(-x)[0] - GRAVITY
    a = acc
    e0 = energy(x, v)
    e_max = e0
    for _ in range(steps):
        acc1 = acc
        for _ in range(200):  # Newton on the new acceleration
            a1 = (af * acc - am * a + (1.0 - af) * acc1) / (1.0 - am)
            x1 = x + h * v + h * h * ((0.5 - beta) * a + beta * a1)
            f, k = law(-x1)
            residual = acc1 - f + GRAVITY
            jacobian = 1.0 + k * h * h * beta * (1.0 - af) / (1.0 - am)
            step = -residual / jacobian
            acc1 += step
            if abs(step) < 1e-13:
                break
        a1 = (af * acc - am * a + (1.0 - af) * acc1) / (1.0 - am)
        x1 = x + h * v + h * h * ((0.5 - beta) * a + beta * a1)
        v1 = v + h * ((1.0 - gamma) * a + gamma * a1)
        x, v, a, acc = x1, v1, a1, acc1
        e_max = max(e_max, energy(x, v))
    return e_max / e0


def main():
    print("rho_inf omega_h largest_energy/start")
    for rho in (0.9, 0.5):
        for omega_h in (0.3, 0.7, 1.0, 1.5, 3.0, 5.0, 10.0):
            print(f"{rho} {omega_h} {largest_energy_ratio(omega_h, rho):.3g}")


if __name__ == "__main__":
    main()

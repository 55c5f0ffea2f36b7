"""Analytic oracles shared by the test files (Housner's free rocking of a rigid block)."""
import math

from scipy.integrate import quad


def quarter_period(theta0, p, alpha):
    """Exact time from θ0 (at rest) to θ = 0 in free rocking. [s]

    T/4 = ∫_0^θ0 dθ / √(2p²[cos(α−θ0) − cos(α−θ)]); with θ = θ0(1 − v²) the integrand is
    regular: cos(α−θ0) − cos(α−θ) = 2 sin(α − θ0 + θ0v²/2)·sin(θ0v²/2).
    """
    def integrand(v):
        x = 0.5 * theta0 * v * v
        sin_ratio = math.sin(x) / (v * v) if v > 0 else 0.5 * theta0
        return 2 * theta0 / math.sqrt(4 * p * p * math.sin(alpha - theta0 + x) * sin_ratio)
    return quad(integrand, 0.0, 1.0, epsabs=0.0, epsrel=1e-13)[0]

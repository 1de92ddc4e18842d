"""The dimensionless normal outputs every fast sweep path gives (one definition, read by all of them)."""

#: Times tau = t / T, the largest compression x_m = delta_m / (v_n T), the rebound rate y_f = -v_f / v_n, and
#: y_p, the rate where P first falls to 0 (1 - y_p is the impulse of P+ over m v_n); T = 1 / w, the law's
#: time scale.
NORMAL_OUTPUTS = ("tau_m", "x_m", "tau_f", "y_f", "y_p")

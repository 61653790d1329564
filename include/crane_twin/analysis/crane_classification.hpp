// A crane's classes of use after ISO 4301-1:2016 (the same classes as EN 13001-1): how many
// working cycles it makes over its design life (class U, Table 1) and how heavy they are (class
// Q of the load spectrum factor k_Q = sum (m_i / m_max)^3 / n, Table 2). docs/fatigue.md
// "Classes".
#pragma once

#include <string>

namespace crane_twin {

/// Class U of `cycles` working cycles (>= 0): U0 up to 1.6e4, then U1 .. U9 with the upper
/// bounds 3.15e4, 6.3e4, 1.25e5, 2.5e5, 5e5, 1e6, 2e6, 4e6, 8e6 (each bound in its class);
/// "above_U9" beyond 8e6. Throws std::invalid_argument for a negative or non-finite count.
std::string utilisationClass(double cycles);

/// Class Q of the load spectrum factor `k_q` (>= 0): Q0 up to 0.0313, then Q1 .. Q5 with the
/// upper bounds 0.0625, 0.125, 0.25, 0.5, 1 (each bound in its class); "above_Q5" beyond 1 (loads
/// heavier than the crane's max_load). Throws std::invalid_argument for a negative or
/// non-finite factor.
std::string loadSpectrumClass(double k_q);

}  // namespace crane_twin

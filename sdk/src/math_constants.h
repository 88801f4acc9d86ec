// pi for the C++ side, from the literal the shaders read (common/shader_interface.h), so that CPU mirrors of
// shader arithmetic (the FFAO grid, LSAO's and SAO's angles) start from the same digits.
#ifndef OBSCURA_MATH_CONSTANTS_H
#define OBSCURA_MATH_CONSTANTS_H

#include "common/shader_interface.h"

namespace obscura {

constexpr double kPi = OBSCURA_PI;
constexpr double kTwoPi = 2.0 * kPi;  // exact: doubling does not round

}  // namespace obscura

#endif  // OBSCURA_MATH_CONSTANTS_H

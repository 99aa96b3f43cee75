#pragma once

// The measured walls' length errors beside the Bayes matcher's wall model: how far a sensed
// wall's length falls from the true edges between its ends, by what bounds it (a door read
// with its class, a door read mis-sized, a corner or another node, or a missed door inside),
// with the matcher's standard deviation for those walls (SensingNoise::WallSigmaIn).

#include <iosfwd>

#include "recovery/error_model.h"
#include "whereami/edge_errors.h"

namespace stickrep::whereami {

// One line per kind of wall: count, mean and standard deviation of sensed minus true, the
// share off by more than 3 and 6 in, and the root mean square of the errors in units of the
// matcher's sigma (1 when the walls are read as the matcher weighs them).
void PrintWallResiduals(const EdgeErrorCounts& total, const recovery::SensingNoise& noise,
                        std::ostream& out);

}  // namespace stickrep::whereami

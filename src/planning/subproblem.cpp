#include "earc/planning/subproblem.hpp"

namespace earc {

bool ConfigBox::contains(const double* q) const {
  for (std::size_t j = 0; j < lo.size(); ++j)
    if (q[j] < lo[j] || q[j] > hi[j]) return false;
  return true;
}

}  // namespace earc

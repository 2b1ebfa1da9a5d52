// The engine instantiated for every roller type (docs/architecture.md, "The roller as a
// component"): the flow, and the drivers written against a roller (the variational equations,
// shooting, the transient steady-state search and the sampling, in their headers). A new roller
// adds its Dynamics specialisation (src/roller/<roller>.hpp, .cpp) and its line here.
#include "flow/hybrid_flow.hpp"
#include "roller/oscillation_drum.hpp"
#include "roller/unilateral_drum.hpp"

namespace oscidrum {

template class BasicFlow<OscillationDrum>;
template class BasicFlow<UnilateralDrum>;

}  // namespace oscidrum

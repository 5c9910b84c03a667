#include "vtrack/smc/mcmc.hpp"

namespace vtrack::smc {

void validate(const ChainParams& p) {
  require(p.samples >= 1, "samples", p.samples, ">= 1");
  require(p.burn_in >= 0, "burn_in", p.burn_in, ">= 0");
  require(p.thinning >= 1, "thinning", p.thinning, ">= 1");
}

void validate(const McmcParams& p) {
  require(p.n_particles >= 1, "n_particles", p.n_particles, ">= 1");
  require(p.burn_in >= 0, "burn_in", p.burn_in, ">= 0");
  require(p.thinning >= 1, "thinning", p.thinning, ">= 1");
  require(p.proposal_scale > 0.0 && std::isfinite(p.proposal_scale), "proposal_scale",
          p.proposal_scale, "positive and finite");
}

McmcReference parse_mcmc_reference(const std::string& name) {
  if (name == "all") return McmcReference::All;
  if (name == "random") return McmcReference::Random;
  if (name == "map") return McmcReference::Map;
  if (name == "mean") return McmcReference::Mean;
  throw InvalidArgument("reference must be 'all', 'random', 'map' or 'mean', got '" + name + "'");
}

const char* to_string(McmcReference reference) {
  switch (reference) {
    case McmcReference::All: return "all";
    case McmcReference::Random: return "random";
    case McmcReference::Map: return "map";
    case McmcReference::Mean: return "mean";
  }
  return "unknown";
}

}  // namespace vtrack::smc

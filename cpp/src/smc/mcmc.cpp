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

const std::vector<std::pair<std::string, McmcReference>>& mcmc_reference_names() {
  static const std::vector<std::pair<std::string, McmcReference>> names{
      {"all", McmcReference::All},
      {"random", McmcReference::Random},
      {"map", McmcReference::Map},
      {"mean", McmcReference::Mean}};
  return names;
}

McmcReference parse_mcmc_reference(const std::string& name) {
  for (const auto& [text, value] : mcmc_reference_names()) {
    if (text == name) return value;
  }
  throw InvalidArgument("reference must be 'all', 'random', 'map' or 'mean', got '" + name + "'");
}

const char* to_string(McmcReference reference) {
  for (const auto& [text, value] : mcmc_reference_names()) {
    if (value == reference) return text.c_str();
  }
  return "unknown";
}

const core::ParameterTable<McmcParams>& McmcParams::table() {
  using P = McmcParams;
  static const auto t = core::ParameterTable<P>()
                            .add("n_particles", &P::n_particles)
                            .add("burn_in", &P::burn_in)
                            .add("thinning", &P::thinning)
                            .add_choice("reference", &P::reference, mcmc_reference_names())
                            .add("proposal_scale", &P::proposal_scale)
                            .add("seed", &P::seed);
  return t;
}

}  // namespace vtrack::smc

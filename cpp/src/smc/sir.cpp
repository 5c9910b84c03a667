#include "vtrack/smc/sir.hpp"

namespace vtrack::smc {

const core::ParameterTable<SirParams>& SirParams::table() {
  using P = SirParams;
  static const auto t = core::ParameterTable<P>()
                            .add("n_particles", &P::n_particles)
                            .add_choice("resampling", &P::resampling, core::resampling_scheme_names())
                            .add("ess_threshold", &P::ess_threshold)
                            .add("resample_move_steps", &P::resample_move_steps)
                            .add("move_scale", &P::move_scale)
                            .add("threads", &P::threads)
                            .add("seed", &P::seed);
  return t;
}

void validate(const SirParams& p) {
  require(p.n_particles >= 1, "n_particles", p.n_particles, ">= 1");
  require(p.ess_threshold >= 0.0 && p.ess_threshold <= 1.0, "ess_threshold", p.ess_threshold,
          "in [0, 1]");
  require(p.resample_move_steps >= 0, "resample_move_steps", p.resample_move_steps, ">= 0");
  require(p.move_scale > 0.0 && std::isfinite(p.move_scale), "move_scale", p.move_scale,
          "positive and finite");
  require(p.threads >= 0, "threads", p.threads, ">= 0");
}

Eigen::MatrixXd sample_prior(const core::Gaussian& prior, Eigen::Index n, BlockStreams& streams,
                             int threads) {
  const Eigen::Index d = prior.dim();
  Eigen::MatrixXd x(n, d);
  const Eigen::Index blocks = block_count(n);
  streams.reserve(blocks);
  const Eigen::MatrixXd Lt = prior.cholesky().transpose();
  for_blocks(blocks, threads, [&](Eigen::Index b) {
    const BlockRange r = block_range(b, n);
    Eigen::MatrixXd eps(r.size(), d);
    for (Eigen::Index k = 0; k < d; ++k) streams[b].fill_normal(&eps(0, k), r.size());
    // Rows x_i = m + L eps_i.
    x.middleRows(r.begin, r.size()) = eps * Lt;
    x.middleRows(r.begin, r.size()).rowwise() += prior.mean().transpose();
  });
  return x;
}

}  // namespace vtrack::smc

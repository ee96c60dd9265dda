#include "bench/fleet/sim_servers.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>

namespace fleetmap::bench {
namespace {

constexpr std::chrono::seconds kStartTimeout{20};
constexpr double kBeyond = 100000.0;  // metres: the outer strips reach this far

Status WaitListening(const process::Subprocess& server, const std::string& name) {
  if (!server.started()) return UnavailableError("could not start " + name);
  if (!server.WaitForOutput("listening", kStartTimeout)) {
    return UnavailableError(name + " did not start: " + server.Output());
  }
  return Status::Ok();
}

}  // namespace

std::vector<ShardRegion> TerrainStrips(double size, int shards) {
  std::vector<ShardRegion> strips;
  for (int i = 0; i < shards; ++i) {
    const double min_x = i == 0 ? -kBeyond : size * i / shards;
    const double max_x = i == shards - 1 ? kBeyond : size * (i + 1) / shards;
    strips.push_back(ShardRegion{fmt::format("shard{}", i), min_x, -kBeyond, max_x, kBeyond});
  }
  return strips;
}

StatusOr<std::unique_ptr<SimServers>> SimServers::Start(
    const std::vector<std::string>& server_args, const std::map<std::string, std::string>& env,
    double terrain_size, int shards) {
  std::unique_ptr<SimServers> self(new SimServers());
  const auto start = [&](std::vector<std::string> more) {
    std::vector<std::string> argv = server_args;
    argv.insert(argv.end(), more.begin(), more.end());
    return std::make_unique<process::Subprocess>(std::move(argv), env);
  };
  if (shards < 2) {
    self->fusing_.push_back(start({}));
    self->names_.push_back("fleetmap-server");
    FLEETMAP_RETURN_IF_ERROR(WaitListening(*self->fusing_.back(), "fleetmap-server"));
    return self;
  }
  self->regions_ = TerrainStrips(terrain_size, shards);
  self->shards_file_ = (std::filesystem::temp_directory_path() /
                        fmt::format("fleetmap-sim-shards-{}-{}.yaml", getpid(),
                                    std::chrono::steady_clock::now().time_since_epoch().count()))
                           .string();
  {
    std::ofstream file(self->shards_file_);
    file << "shards:\n";
    for (const ShardRegion& region : self->regions_) {
      file << fmt::format("  {}: [{}, {}, {}, {}]\n", region.name, region.min_x, region.min_y,
                          region.max_x, region.max_y);
    }
    if (!file) return UnavailableError("could not write " + self->shards_file_);
  }
  for (const ShardRegion& region : self->regions_) {
    self->fusing_.push_back(
        start({"--shards", self->shards_file_, "--shard", region.name, "--name", region.name}));
    self->names_.push_back(region.name);
  }
  self->aggregator_ = start({"--shards", self->shards_file_, "--aggregate"});
  // The reference fuses everything as a shard of its own (its grid on its own topic); its fused
  // tiles, weaker than the shards', reach no reader.
  self->reference_ =
      start({"--shard", kReferenceShard, "--region", fmt::format("{}", -kBeyond),
             fmt::format("{}", -kBeyond), fmt::format("{}", kBeyond), fmt::format("{}", kBeyond),
             "--name", kReferenceShard, "--ownership-strength", "1", "--no-object-learning",
             "--no-extrapolation"});
  for (size_t i = 0; i < self->fusing_.size(); ++i) {
    FLEETMAP_RETURN_IF_ERROR(WaitListening(*self->fusing_[i], self->names_[i]));
  }
  FLEETMAP_RETURN_IF_ERROR(WaitListening(*self->reference_, "the reference server"));
  if (!self->aggregator_->started()) return UnavailableError("could not start the aggregator");
  return self;
}

SimServers::~SimServers() {
  Stop();
  if (!shards_file_.empty()) {
    std::error_code error;
    std::filesystem::remove(shards_file_, error);
  }
}

double SimServers::CpuSeconds() const {
  double sum = 0.0;
  for (const auto& server : fusing_) {
    if (const auto usage = process::ReadUsage(server->pid())) sum += usage->cpu_seconds;
  }
  return sum;
}

int64_t SimServers::RssBytes() const {
  int64_t sum = 0;
  for (const auto& server : fusing_) {
    if (const auto usage = process::ReadUsage(server->pid())) sum += usage->rss_bytes;
  }
  return sum;
}

int64_t SimServers::PeakRssBytes() const {
  int64_t sum = 0;
  for (const auto& server : fusing_) {
    if (const auto usage = process::ReadUsage(server->pid())) sum += usage->peak_rss_bytes;
  }
  return sum;
}

std::string SimServers::Output() const {
  if (fusing_.size() == 1 && !reference_) return fusing_[0]->Output();
  std::string out;
  for (size_t i = 0; i < fusing_.size(); ++i) {
    out += "=== " + names_[i] + "\n" + fusing_[i]->Output();
  }
  if (aggregator_) out += "=== aggregator\n" + aggregator_->Output();
  if (reference_) out += "=== reference server\n" + reference_->Output();
  return out;
}

void SimServers::Stop() {
  std::vector<process::Subprocess*> all;
  for (auto& server : fusing_) all.push_back(server.get());
  if (aggregator_) all.push_back(aggregator_.get());
  if (reference_) all.push_back(reference_.get());
  for (process::Subprocess* server : all) server->Signal(SIGINT);
  for (process::Subprocess* server : all) server->Wait(std::chrono::seconds(10));
}

}  // namespace fleetmap::bench

#include "optimizer/task_codec.h"

#include <nlohmann/json.hpp>

#include "engine/core/error.h"

namespace fibrenet::optimizer {

using nlohmann::json;

std::string EncodeTask(const Task& task, std::size_t index) {
  json j;
  j["index"] = index;
  j["design"] = task.design;
  j["fidelity"] = {{"name", task.fidelity.name},
                   {"overrides", task.fidelity.overrides},
                   {"replicates", task.fidelity.replicates},
                   {"top", task.fidelity.top}};
  j["seed"] = task.seed;
  return j.dump();
}

Task DecodeTask(const std::string& text, std::size_t* index) {
  try {
    const json j = json::parse(text);
    Task task;
    *index = j.at("index").get<std::size_t>();
    task.design = j.at("design").get<Design>();
    const json& f = j.at("fidelity");
    task.fidelity.name = f.at("name").get<std::string>();
    task.fidelity.overrides = f.at("overrides").get<std::map<std::string, double>>();
    task.fidelity.replicates = f.at("replicates").get<int>();
    task.fidelity.top = f.at("top").get<int>();
    task.seed = j.at("seed").get<std::uint64_t>();
    return task;
  } catch (const json::exception& e) {
    throw Error(std::string("malformed task message: ") + e.what());
  }
}

std::string EncodeReply(const WorkerReply& reply) {
  json j;
  j["index"] = reply.result.index;
  j["wall_s"] = reply.result.wall_s;
  j["ok"] = reply.result.result.ok;
  j["reason"] = reply.result.result.reason;
  j["metrics"] = reply.result.result.metrics;
  j["units"] = reply.result.result.units;
  json artifacts = json::array();
  for (const ArtifactPath& a : reply.result.result.artifacts) {
    artifacts.push_back({{"kind", a.kind}, {"path", a.path}});
  }
  j["artifacts"] = artifacts;
  j["fatal"] = reply.fatal;
  j["input_error"] = reply.input_error;
  j["message"] = reply.message;
  return j.dump();
}

WorkerReply DecodeReply(const std::string& text) {
  try {
    const json j = json::parse(text);
    WorkerReply reply;
    reply.result.index = j.at("index").get<std::size_t>();
    reply.result.wall_s = j.at("wall_s").get<double>();
    EvaluationResult& r = reply.result.result;
    r.ok = j.at("ok").get<bool>();
    r.reason = j.at("reason").get<std::string>();
    r.metrics = j.at("metrics").get<std::map<std::string, double>>();
    r.units = j.at("units").get<std::map<std::string, std::string>>();
    for (const json& a : j.at("artifacts")) {
      r.artifacts.push_back({a.at("kind").get<std::string>(), a.at("path").get<std::string>()});
    }
    reply.fatal = j.at("fatal").get<bool>();
    reply.input_error = j.at("input_error").get<bool>();
    reply.message = j.at("message").get<std::string>();
    return reply;
  } catch (const json::exception& e) {
    throw Error(std::string("malformed result message: ") + e.what());
  }
}

}  // namespace fibrenet::optimizer

#include "gl/timers.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "gl/context.h"

namespace voxgi::gl {

Summary summarize(std::vector<double> v) {
    Summary s;
    if (v.empty()) return s;
    v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
    if (v.empty()) return {std::nan(""), std::nan(""), std::nan("")};
    std::sort(v.begin(), v.end());
    s.min = v.front();
    s.max = v.back();
    std::size_t n = v.size();
    s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    return s;
}

StageTimers::~StageTimers() {
    for (const Pending& p : pending_) glDeleteQueries(1, &p.query);
    if (!freeQueries_.empty()) glDeleteQueries(GLsizei(freeQueries_.size()), freeQueries_.data());
}

void StageTimers::begin(const std::string& stage) {
    if (!current_.empty()) throw GlError("timer stage '" + stage + "' begun inside '" + current_ + "'");
    current_ = stage;
    if (freeQueries_.empty()) {
        GLuint q = 0;
        glGenQueries(1, &q);
        freeQueries_.push_back(q);
    }
    currentQuery_ = freeQueries_.back();
    freeQueries_.pop_back();
    if (std::find(order_.begin(), order_.end(), stage) == order_.end()) order_.push_back(stage);
    glBeginQuery(GL_TIME_ELAPSED, currentQuery_);
    start_ = std::chrono::steady_clock::now();
}

void StageTimers::end() {
    glEndQuery(GL_TIME_ELAPSED);
    double cpu = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    pending_.push_back({current_, currentQuery_, cpu, start_});
    current_.clear();
}

void StageTimers::addCpu(const std::string& stage, double ms) {
    if (std::find(order_.begin(), order_.end(), stage) == order_.end()) order_.push_back(stage);
    pendingCpu_[stage] += ms;
}

void StageTimers::collect() {
    struct FrameSum {
        double gpuMs = 0.0, cpuMs = 0.0;
    };
    std::map<std::string, FrameSum> gpuStages;
    for (const Pending& p : pending_) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(p.query, GL_QUERY_RESULT, &ns);
        const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - p.begun).count();
        const double gpuMs = double(ns) * 1e-6;
        FrameSum& f = gpuStages[p.stage];
        f.gpuMs += gpuMs <= wallMs ? gpuMs : std::nan("");
        f.cpuMs += p.cpuMs;
        freeQueries_.push_back(p.query);
    }
    pending_.clear();
    for (const auto& [stage, f] : gpuStages) {
        samples_[stage].gpuMs.push_back(f.gpuMs);
        samples_[stage].cpuMs.push_back(f.cpuMs);
    }
    for (const auto& [stage, ms] : pendingCpu_) samples_[stage].cpuMs.push_back(ms);
    pendingCpu_.clear();
}

std::string StageTimers::toJson() const {
    auto summary = [](const std::vector<double>& v) {
        Summary s = summarize(v);
        return nlohmann::ordered_json{{"min", s.min}, {"median", s.median}, {"max", s.max}};
    };
    nlohmann::ordered_json stages = nlohmann::ordered_json::object();
    for (const std::string& stage : order_) {
        auto it = samples_.find(stage);
        if (it == samples_.end()) continue;
        nlohmann::ordered_json j;
        if (!it->second.gpuMs.empty()) j["gpu_ms"] = summary(it->second.gpuMs);
        j["cpu_ms"] = summary(it->second.cpuMs);
        j["frames"] = it->second.cpuMs.size();
        stages[stage] = j;
    }
    return nlohmann::ordered_json{{"stages", stages}}.dump(2) + "\n";
}

}  // namespace voxgi::gl

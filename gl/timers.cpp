#include "gl/timers.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "gl/context.h"

namespace voxgi::gl {

Summary summarize(std::vector<double> v) {
    Summary s;
    if (v.empty()) return s;
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
    pending_.push_back({current_, currentQuery_, cpu});
    current_.clear();
}

void StageTimers::addCpu(const std::string& stage, double ms) {
    if (std::find(order_.begin(), order_.end(), stage) == order_.end()) order_.push_back(stage);
    samples_[stage].cpuMs.push_back(ms);
}

void StageTimers::collect() {
    for (const Pending& p : pending_) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(p.query, GL_QUERY_RESULT, &ns);
        StageSamples& s = samples_[p.stage];
        s.gpuMs.push_back(double(ns) * 1e-6);
        s.cpuMs.push_back(p.cpuMs);
        freeQueries_.push_back(p.query);
    }
    pending_.clear();
}

std::string StageTimers::toJson() const {
    std::ostringstream out;
    auto summary = [&](const char* key, const std::vector<double>& v) {
        Summary s = summarize(v);
        char buf[160];
        std::snprintf(buf, sizeof buf, "\"%s\": {\"min\": %.4f, \"median\": %.4f, \"max\": %.4f}", key, s.min,
                      s.median, s.max);
        out << buf;
    };
    out << "{\n  \"stages\": {\n";
    bool first = true;
    for (const std::string& stage : order_) {
        auto it = samples_.find(stage);
        if (it == samples_.end()) continue;
        out << (first ? "" : ",\n") << "    \"" << stage << "\": {";
        first = false;
        if (!it->second.gpuMs.empty()) {
            summary("gpu_ms", it->second.gpuMs);
            out << ", ";
        }
        summary("cpu_ms", it->second.cpuMs);
        out << ", \"frames\": " << it->second.cpuMs.size() << "}";
    }
    out << "\n  }\n}\n";
    return out.str();
}

}  // namespace voxgi::gl

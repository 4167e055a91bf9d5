// terrasynth/status.h: how the runtime reports failure.
//
// Bad external input (files, JSON, devices) is reported by returning a Status or Result<T> whose
// message names the file or field and the problem. Programmer errors (violated preconditions) abort
// through TERRASYNTH_REQUIRE with a message. Nothing throws across the runtime API.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

namespace terrasynth {

class Status {
public:
    static Status ok() { return Status(); }
    static Status error(std::string message) { return Status(std::move(message)); }

    bool isOk() const { return !failed_; }
    explicit operator bool() const { return isOk(); }
    // Empty when ok. Otherwise one line, e.g. "data/a.png: not a 16-bit grayscale PNG (8-bit RGB)".
    const std::string& message() const { return message_; }

    // Prefixes context such as a file or field name: "db.tsdb: " + message. An empty context adds
    // nothing (never a bare ": ").
    Status withContext(const std::string& context) const {
        return failed_ && !context.empty() ? Status(context + ": " + message_) : *this;
    }

private:
    Status() = default;
    explicit Status(std::string message) : failed_(true), message_(std::move(message)) {}
    bool failed_ = false;
    std::string message_;
};

// A value or an error Status. Access to value() on an error is a programmer error.
template <class T>
class Result {
public:
    Result(T value) : value_(std::move(value)), status_(Status::ok()) {}
    Result(Status error) : status_(std::move(error)) {
        if (status_.isOk()) status_ = Status::error("internal: Result built from an ok Status");
    }

    bool isOk() const { return status_.isOk(); }
    explicit operator bool() const { return isOk(); }
    const Status& status() const { return status_; }
    const std::string& message() const { return status_.message(); }

    T& value() & { check(); return *value_; }
    const T& value() const& { check(); return *value_; }
    T&& value() && { check(); return std::move(*value_); }
    T& operator*() & { check(); return *value_; }
    const T& operator*() const& { check(); return *value_; }
    T* operator->() { check(); return &*value_; }
    const T* operator->() const { check(); return &*value_; }

private:
    void check() const {
        if (!value_) {
            std::fprintf(stderr, "terrasynth: value() of a failed Result: %s\n", status_.message().c_str());
            std::abort();
        }
    }
    std::optional<T> value_;
    Status status_;
};

}  // namespace terrasynth

// Precondition check for programmer errors: prints the condition and message, then aborts.
#define TERRASYNTH_REQUIRE(cond, msg)                                                          \
    do {                                                                                       \
        if (!(cond)) {                                                                         \
            std::fprintf(stderr, "terrasynth: precondition failed at %s:%d: %s (%s)\n",        \
                         __FILE__, __LINE__, #cond, msg);                                      \
            std::abort();                                                                      \
        }                                                                                      \
    } while (0)

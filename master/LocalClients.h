#pragma once

#include <sys/types.h>

#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace igi {

/// The igi-client processes the master starts on its own machine (--local-clients N). They
/// connect back like any remote client. The master waits for them at the end and kills any
/// that outlive the session.
class LocalClients {
  public:
    LocalClients() = default;
    ~LocalClients();
    LocalClients(const LocalClients&) = delete;
    LocalClients& operator=(const LocalClients&) = delete;

    /// Each line a client writes to its stderr, without the newline; called on a reader thread.
    using LineHandler = std::function<void(const std::string&)>;

    /// Starts `count` clients of `executable` with `arguments` and this process's environment
    /// plus `environment` ("NAME=value", replacing a variable of the same name): secrets go
    /// there, not on the command line, where any user could read them. Throws on failure.
    /// With `onStderrLine`, the clients' stderr is a pipe whose lines go to it (the master's
    /// progress line prints them above itself); without, they share the master's stderr. Call
    /// once per LocalClients.
    void start(const std::string& executable, const std::vector<std::string>& arguments, int count,
               const std::vector<std::string>& environment = {}, LineHandler onStderrLine = {});

    /// Waits up to `seconds` for all to exit, then kills the rest. Returns how many had to be
    /// killed.
    int stop(double seconds);

    const std::vector<pid_t>& pids() const { return pids_; }

    /// igi-client beside the running executable.
    static std::string clientExecutableBesideSelf();

  private:
    /// Reads the clients' stderr pipes until every client has closed its own, and hands on
    /// their lines.
    void readLines(std::vector<int> fds, LineHandler onLine);

    std::vector<pid_t> pids_;
    std::thread stderrReader_;
};

}  // namespace igi

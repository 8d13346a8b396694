#pragma once

#include <sys/types.h>
#include <string>
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

    /// Starts `count` clients of `executable` with `arguments` and this process's environment
    /// plus `environment` ("NAME=value", replacing a variable of the same name): secrets go
    /// there, not on the command line, where any user could read them. Throws on failure.
    void start(const std::string& executable, const std::vector<std::string>& arguments, int count,
               const std::vector<std::string>& environment = {});

    /// Waits up to `seconds` for all to exit, then kills the rest. Returns how many had to be
    /// killed.
    int stop(double seconds);

    const std::vector<pid_t>& pids() const { return pids_; }

    /// igi-client beside the running executable.
    static std::string clientExecutableBesideSelf();

  private:
    std::vector<pid_t> pids_;
};

}  // namespace igi

#pragma once

#include <string>
#include <vector>

#include "MasterOptions.h"

namespace igi {

/// How the master starts its local clients (--local-clients N): their command line and the
/// environment variables added to the master's.
struct LocalClientLaunch {
    std::vector<std::string> arguments;
    std::vector<std::string> environment;  ///< "NAME=value"
};

/// The launch of local clients of a master with `options` that listens on `port`. `localSecret`
/// is the random secret the master made for local clients alone ("" if none); `machineThreads`
/// the threads the machine has, shared among the clients unless --client-threads says.
LocalClientLaunch localClientLaunch(const MasterOptions& options, unsigned port,
                                    const std::string& localSecret, unsigned machineThreads);

}  // namespace igi

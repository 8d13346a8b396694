#include "LocalClientLaunch.h"

#include <algorithm>

namespace igi {

LocalClientLaunch localClientLaunch(const MasterOptions& o, unsigned port,
                                    const std::string& localSecret, unsigned machineThreads) {
    const unsigned threads =
        o.clientThreads > 0 ? o.clientThreads
                            : std::max(1u, machineThreads / unsigned(std::max(1, o.localClients)));
    // A master that listens on every interface is reached on loopback by its own clients.
    const std::string host = o.listenHost == "0.0.0.0" ? "127.0.0.1" : o.listenHost;
    LocalClientLaunch launch;
    auto& args = launch.arguments;
    args = {"--connect",   host + ":" + std::to_string(port),
            "--threads",   std::to_string(threads),
            "--log-level", o.clientLogLevel};
    if (o.replayClients) args.push_back("--replay");
    // They load the scene this master loaded and logged: one warning once, not N + 1 times.
    args.push_back("--no-scene-warnings");
    // They belong to this session: when it ends or this master dies, they go too.
    args.insert(args.end(), {"--reconnect-seconds", "0"});
    if (o.insecure) {
        args.push_back("--insecure");
    } else if (!localSecret.empty()) {
        // In the environment, not on the command line, where any user could read it.
        launch.environment.push_back("IGI_SECRET=" + localSecret);
    } else if (!o.secretFile.empty()) {
        args.insert(args.end(), {"--secret-file", o.secretFile.string()});
    }  // else: they inherit IGI_SECRET
    return launch;
}

}  // namespace igi

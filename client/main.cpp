// igi-client: a render client. Connects to a master, receives the scene and renders tiles on
// all cores until the master ends the session.
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "BuildId.h"
#include "ClientSession.h"
#include "util/HostPort.h"
#include "util/LogLevels.h"

int main(int argc, char** argv) {
    CLI::App app{"igi-client: renders tiles for an igi-master"};
    // The identity a master compares at connect; scripts/cluster.sh asks each host for it first.
    app.set_version_flag("--version", igi::buildId(), "print the build identity and exit");
    std::string connect = "127.0.0.1:7878";
    igi::ClientOptions options;
    std::string logLevel = "info";
    app.add_option("--connect", connect, "the master's HOST:PORT")->capture_default_str();
    app.add_option("--threads", options.threads, "render threads (0: every hardware thread)")
        ->capture_default_str();
    app.add_option("--connect-timeout", options.connectTimeoutSeconds,
                   "seconds to keep trying to reach the master")
        ->capture_default_str();
    app.add_option("--read-timeout", options.readTimeoutSeconds,
                   "seconds of silence after which the master is considered gone")
        ->capture_default_str();
    app.add_option("--log-level", logLevel, "trace, debug, info, warn, error, critical or off")
        ->capture_default_str()
        ->transform(CLI::IsMember(igi::logLevelNames(), CLI::ignore_case));
    app.add_flag("--replay", options.replay,
                 "render each tile once, then resend that result whenever the tile is asked for "
                 "again (to measure how many pixels per second the master can take)");
    app.add_option("--secret-file", options.secretFile, "the cluster secret (else IGI_SECRET)");
    app.add_flag("--insecure", options.insecure,
                 "join a master that runs without a secret (loopback tests)");
    app.add_option("--reconnect-seconds", options.reconnectSeconds,
                   "after losing the master, keep trying to reach it (again) this long; 0: exit")
        ->capture_default_str();
    bool quietScene = false;
    app.add_flag("--no-scene-warnings", quietScene,
                 "do not log the scene loader's warnings (the master's local clients: the master "
                 "logged them already)");
    CLI11_PARSE(app, argc, argv);
    options.sceneWarnings = !quietScene;

    spdlog::set_level(spdlog::level::from_str(logLevel));
    spdlog::set_pattern("[%H:%M:%S.%e] [client %P] [%l] %v");
    try {
        const igi::HostPort hp = igi::parseHostPort(connect, "--connect");
        if (hp.port == 0) throw std::invalid_argument("--connect: port 0 is no master's port");
        options.host = hp.host;
        options.port = hp.port;
    } catch (const std::invalid_argument& e) {
        spdlog::error("{}", e.what());
        return 2;
    }
    try {
        for (;;) {
            int code;
            {
                igi::ClientSession session(options);
                code = session.run();
            }
            // A lost master (crashed, restarted, the network cut) is tried again with backoff:
            // the next session connects anew, proves itself and gets the scene again.
            if (code != igi::kLost || options.reconnectSeconds <= 0) return code;
            spdlog::warn("lost the master; trying to reach it again for up to {:.0f} s",
                         options.reconnectSeconds);
            options.connectTimeoutSeconds = options.reconnectSeconds;
        }
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        return 1;
    }
}

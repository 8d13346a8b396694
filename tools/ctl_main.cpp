// igi-ctl: sends one control command to a running igi-master (--control HOST:PORT) and prints
// its reply. Commands and their properties: docs/ANIMATION.md.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>
#include <nlohmann/json.hpp>

#include "BuildId.h"
#include "util/HostPort.h"

namespace {

// One property of a command: the flag, the JSON key, and how many numbers it takes (0: true
// or false, -1: a word).
struct Property {
    const char* flag;
    const char* key;
    int numbers;
};

// What --help shows a property takes: "X Y Z", or a colour's "R G B" (or one grey number).
std::string typeName(const Property& p) {
    const std::string key = p.key;
    const bool colour = key == "intensity" || key == "irradiance" || key == "radiance" ||
                        key == "diffuse" || key == "specular" || key == "transmittance" ||
                        key == "emission";
    if (p.numbers == 0) return "true|false";
    if (p.numbers < 0) return "WORD";
    if (p.numbers == 1) return "NUMBER";
    return colour ? "R G B|GREY" : "X Y Z";
}

// A subcommand that changes something: its properties become keys of the JSON command.
struct ChangeCommand {
    CLI::App* app = nullptr;
    std::string name;  // object, light or material name (empty for the camera)
    std::vector<std::pair<Property, std::vector<double>>> numeric;
    std::vector<std::pair<Property, std::string>> words;
};

// On the heap: CLI11 keeps pointers to the members, which must not move.
std::unique_ptr<ChangeCommand> addChangeCommand(CLI::App& app, const char* command,
                                                const char* help, bool named,
                                                const std::vector<Property>& properties) {
    auto owned = std::make_unique<ChangeCommand>();
    ChangeCommand& c = *owned;
    c.app = app.add_subcommand(command, help);
    if (named) c.app->add_option("name", c.name, "its name in the scene file")->required();
    c.numeric.reserve(properties.size());
    c.words.reserve(properties.size());
    for (const Property& p : properties) {
        if (p.numbers <= 0) {
            c.words.push_back({p, ""});
            auto* option = c.app->add_option(p.flag, c.words.back().second, p.key);
            option->type_name(typeName(p));
            if (p.numbers == 0) option->check(CLI::IsMember({"true", "false"}));
        } else {
            c.numeric.push_back({p, {}});
            c.app->add_option(p.flag, c.numeric.back().second, p.key)
                ->expected(1, p.numbers)
                ->type_name(typeName(p));
        }
    }
    return owned;
}

nlohmann::json toJson(const ChangeCommand& c, const char* cmd) {
    nlohmann::json j{{"cmd", cmd}};
    if (!c.name.empty()) j["name"] = c.name;
    for (const auto& [p, values] : c.numeric) {
        if (values.empty()) continue;
        if (values.size() == 1)
            j[p.key] = values[0];
        else
            j[p.key] = values;
    }
    for (const auto& [p, word] : c.words) {
        if (word.empty()) continue;
        if (word == "true" || word == "false")
            j[p.key] = word == "true";
        else
            j[p.key] = word;
    }
    return j;
}

std::string exchange(const igi::HostPort& master, const std::string& line) {
    boost::asio::io_context io;
    boost::asio::ip::tcp::resolver resolver(io);
    boost::asio::ip::tcp::socket socket(io);
    const std::string address = master.host + ":" + std::to_string(master.port);
    try {
        boost::asio::connect(socket, resolver.resolve(master.host, std::to_string(master.port)));
    } catch (const boost::system::system_error& e) {
        // "connect: Connection refused" alone does not say what was tried.
        throw std::runtime_error("--connect " + address +
                                 ": cannot reach the master: " + e.code().message() +
                                 " (is igi-master running with --control " + address + "?)");
    }
    boost::asio::write(socket, boost::asio::buffer(line + "\n"));
    boost::asio::streambuf buffer;
    boost::asio::read_until(socket, buffer, '\n');
    std::string reply(boost::asio::buffers_begin(buffer.data()),
                      boost::asio::buffers_end(buffer.data()));
    return reply.substr(0, reply.find('\n'));
}

// `settings KEY VALUE ...`: the pairs as a command's keys. A value that reads as JSON (64,
// 0.5, true, [2, 2]) is that; any other word is a string (tree, kollig-keller).
nlohmann::json settingsCommand(const std::vector<std::string>& pairs) {
    if (pairs.empty()) throw CLI::ValidationError("settings", "expected KEY VALUE pairs");
    if (pairs.size() % 2 != 0)
        throw CLI::ValidationError("settings",
                                   "expected KEY VALUE pairs, got an odd number of words (" +
                                       std::to_string(pairs.size()) + ")");
    nlohmann::json j{{"cmd", "settings"}};
    for (std::size_t i = 0; i < pairs.size(); i += 2) {
        nlohmann::json value = nlohmann::json::parse(pairs[i + 1], nullptr, false);
        j[pairs[i]] = value.is_discarded() ? nlohmann::json(pairs[i + 1]) : value;
    }
    return j;
}

// `status --table`: what scripts/cluster.sh reads with `read`, one record per line.
void printTable(const nlohmann::json& status) {
    std::cout << "session " << status.value("frames_done", 0) << ' '
              << status.value("frames_total", 0) << ' ' << status.value("fps", 0.0) << ' '
              << status.value("clients", 0) << '\n';
    for (const nlohmann::json& c : status.value("client_list", nlohmann::json::array()))
        std::cout << "client " << c.value("address", "?") << ' ' << c.value("threads", 0) << ' '
                  << c.value("tiles_per_s", 0.0) << ' ' << c.value("mrays_per_s", 0.0) << ' '
                  << c.value("host", "?") << '\n';
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"igi-ctl: controls a running igi-master (started with --control HOST:PORT)"};
    app.set_version_flag("--version", igi::buildId(), "print the build identity and exit");
    std::string connect = "127.0.0.1:7879";
    app.add_option("--connect", connect, "the master's control HOST:PORT")->capture_default_str();
    app.require_subcommand(1);

    auto camera = addChangeCommand(app, "camera", "moves the camera", false,
                                   {{"--position", "position", 3},
                                    {"--look-at", "look_at", 3},
                                    {"--up", "up", 3},
                                    {"--fov-y", "fov_y", 1}});
    auto object =
        addChangeCommand(app, "object", "moves an object (a mesh of the scene file)", true,
                         {{"--translate", "translate", 3},
                          {"--rotate-deg", "rotate_deg", 3},
                          {"--scale", "scale", 3}});
    auto light = addChangeCommand(app, "light", "changes a light", true,
                                  {{"--position", "position", 3},
                                   {"--intensity", "intensity", 3},
                                   {"--corner", "corner", 3},
                                   {"--edge1", "edge1", 3},
                                   {"--edge2", "edge2", 3},
                                   {"--radiance", "radiance", 3},
                                   {"--direction", "direction", 3},
                                   {"--irradiance", "irradiance", 3},
                                   {"--on", "on", 0}});
    auto material =
        addChangeCommand(app, "material", "changes a material (every one of that name)", true,
                         {{"--diffuse", "diffuse", 3},
                          {"--specular", "specular", 3},
                          {"--phong-exponent", "phong_exponent", 1},
                          {"--ior", "ior", 1},
                          {"--transmittance", "transmittance", 3},
                          {"--emission", "emission", 3},
                          {"--roughness", "roughness", 1},
                          {"--metallic", "metallic", 1},
                          {"--type", "type", -1}});
    auto environment =
        addChangeCommand(app, "environment",
                         "changes the environment: a map's scale, a constant sky's radiance", false,
                         {{"--scale", "scale", 3},
                          {"--radiance", "radiance", 3},
                          {"--rotate-deg", "rotate_deg", 1}});
    auto* settings = app.add_subcommand(
        "settings",
        "changes render settings at the next frame, as a scene file's \"render\" keys: "
        "settings indirect_vpls 64 light_sampling tree (the reply lists the settings in force)");
    // Every word after the subcommand is a key or a value: a negative value (-1) is not an
    // option (igi-master refuses it, naming the key and its range).
    settings->prefix_command();
    settings->footer(
        "KEY VALUE ...: a scene file's \"render\" keys and their values, and target_error "
        "(docs/ANIMATION.md, \"Render settings while it runs\")");
    auto* status =
        app.add_subcommand("status", "frames done, epoch, accumulated frames, clients, fps");
    bool table = false;
    status->add_flag("--table", table,
                     "print lines for scripts instead of JSON: 'session FRAMES_DONE FRAMES_TOTAL "
                     "FPS CLIENTS', then 'client ADDRESS:PORT THREADS TILES_PER_S MRAYS_PER_S "
                     "HOSTNAME' for each");
    auto* scene = app.add_subcommand("scene", "the scene's objects, lights and camera");
    float pickX = 0, pickY = 0;
    auto* pick = app.add_subcommand("pick", "the object under an image position");
    pick->add_option("x", pickX, "pixels from the left")->required();
    pick->add_option("y", pickY, "pixels from the top")->required();
    float stops = 0;
    auto* exposure = app.add_subcommand(
        "exposure", "the display exposure of the view and of PNG images written from now on");
    exposure->add_option("stops", stops, "in stops")->required();
    std::string snapshotPath;
    auto* snapshot = app.add_subcommand(
        "snapshot",
        "writes the next frame to a file (.png or .exr; without one, a new .exr beside the "
        "master's --output or in out/); the reply gives its whole path");
    snapshot->add_option("path", snapshotPath, "relative to the master's working folder");
    auto* stop = app.add_subcommand("stop", "ends the session (the master writes its outputs)");
    std::string raw;
    auto* send = app.add_subcommand("send", "sends a JSON command as it is");
    send->add_option("json", raw)->required();
    CLI11_PARSE(app, argc, argv);

    nlohmann::json command;
    if (*camera->app) command = toJson(*camera, "camera");
    if (*object->app) command = toJson(*object, "object");
    if (*light->app) command = toJson(*light, "light");
    if (*material->app) command = toJson(*material, "material");
    if (*environment->app) command = toJson(*environment, "environment");
    if (*status) command = {{"cmd", "status"}};
    if (*settings) {
        try {
            command = settingsCommand(settings->remaining());
        } catch (const CLI::ValidationError& e) {
            return app.exit(e);
        }
    }
    if (*scene) command = {{"cmd", "scene"}};
    if (*pick) command = {{"cmd", "pick"}, {"x", pickX}, {"y", pickY}};
    if (*exposure) command = {{"cmd", "exposure"}, {"stops", stops}};
    if (*snapshot) {
        command = {{"cmd", "snapshot"}};
        if (!snapshotPath.empty()) command["path"] = snapshotPath;
    }
    if (*stop) command = {{"cmd", "stop"}};
    try {
        const std::string line = *send ? raw : command.dump();
        const std::string reply = exchange(igi::parseHostPort(connect, "--connect"), line);
        const auto parsed = nlohmann::json::parse(reply, nullptr, false);
        const bool ok = parsed.is_object() && parsed.value("ok", false);
        if (table && ok)
            printTable(parsed);
        else
            std::cout << reply << '\n';
        return ok ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "igi-ctl: " << e.what() << '\n';
        return 2;
    }
}

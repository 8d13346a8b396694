#include "Animation.h"

#include <algorithm>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "SceneNames.h"
#include "SceneProperties.h"
#include "scene/JsonReader.h"
#include "scene/SceneError.h"

namespace igi {

namespace {

/// One keyframe of one object: the values it gives (its other fields are unused) and which.
template <typename T>
struct Key {
    std::uint32_t frame = 0;
    T value{};
    PropertyMask given = 0;
    std::string path;  ///< the keyframe's JSON path, for messages
};

/// The keyframes of one object. Each property is interpolated between the keyframes that give
/// it, independently of the others.
template <typename T>
class Track {
  public:
    Track(std::string file, std::string path, std::vector<Key<T>> keys)
        : file_(std::move(file)), path_(std::move(path)), keys_(std::move(keys)) {
        byProperty_.resize(propertyTable<T>().properties.size());
        for (std::size_t k = 0; k < keys_.size(); ++k) {
            for (std::size_t p = 0; p < byProperty_.size(); ++p) {
                if (keys_[k].given & (PropertyMask{1} << p)) byProperty_[p].push_back(k);
            }
        }
    }

    bool empty() const { return keys_.empty(); }
    std::uint32_t firstFrame() const { return keys_.front().frame; }
    std::uint32_t lastFrame() const { return keys_.back().frame; }
    const std::string& path() const { return path_; }

    /// `base` with every property this track keys set to its value at `frame`.
    T valueAt(std::uint32_t frame, const T& base) const {
        T out = base;
        const auto& properties = propertyTable<T>().properties;
        for (std::size_t p = 0; p < properties.size(); ++p) {
            const std::vector<std::size_t>& keys = byProperty_[p];
            if (keys.empty()) continue;
            // The first key of this property after `frame`.
            const auto next = std::upper_bound(
                keys.begin(), keys.end(), frame,
                [&](std::uint32_t f, std::size_t k) { return f < keys_[k].frame; });
            if (next == keys.begin()) {  // before the first: hold the first
                properties[p].blend(keys_[keys.front()].value, keys_[keys.front()].value, 0.0f,
                                    out);
                continue;
            }
            const Key<T>& a = keys_[*(next - 1)];
            if (next == keys.end() || properties[p].steps || a.frame == frame) {
                properties[p].blend(a.value, a.value, 0.0f, out);
                continue;
            }
            const Key<T>& b = keys_[*next];
            // In double: frame differences up to kMaxFrame stay exact.
            const auto t = static_cast<float>(static_cast<double>(frame - a.frame) /
                                              static_cast<double>(b.frame - a.frame));
            properties[p].blend(a.value, b.value, t, out);
        }
        return out;
    }

    /// Throws if some frame from the first keyframe to the last gives an unusable value with
    /// `base` for what the track does not key. Outside that range every property holds, so
    /// the value is that of the first or last keyframe's frame.
    void checkEveryFrame(const T& base) const {
        if (empty()) return;
        for (std::uint32_t f = firstFrame(); f <= lastFrame(); ++f) {
            if (auto problem = propertyTable<T>().problem(valueAt(f, base))) fail(f, *problem);
            if (f == lastFrame()) break;  // (lastFrame may be the largest uint32)
        }
    }

    /// The first frame from the first keyframe to the last at which `test` holds for the value.
    template <typename Test>
    std::optional<std::uint32_t> firstFrameWhere(const T& base, Test&& test) const {
        if (empty()) return std::nullopt;
        for (std::uint32_t f = firstFrame(); f <= lastFrame(); ++f) {
            if (test(valueAt(f, base))) return f;
            if (f == lastFrame()) break;
        }
        return std::nullopt;
    }

  private:
    // At a keyframe's frame the error names that keyframe (and the first responsible key it
    // gives); between keyframes it names the array and the frame.
    [[noreturn]] void fail(std::uint32_t frame, const PropertyProblem& problem) const {
        for (const Key<T>& key : keys_) {
            if (key.frame != frame) continue;
            for (const char* name : problem.keys) {
                const int bit = propertyTable<T>().indexOf(name);
                if (bit >= 0 && (key.given & (PropertyMask{1} << bit))) {
                    throw SceneError::atPath(file_, key.path + "/" + name, problem.message);
                }
            }
            throw SceneError::atPath(file_, key.path, problem.message);
        }
        const auto after =
            std::upper_bound(keys_.begin(), keys_.end(), frame,
                             [](std::uint32_t f, const Key<T>& k) { return f < k.frame; });
        std::ostringstream where;
        where << "at frame " << frame << " (interpolated between the keyframes of frames "
              << (after - 1)->frame << " and " << after->frame << "): " << problem.message;
        throw SceneError::atPath(file_, path_, where.str());
    }

    std::string file_;
    std::string path_;
    std::vector<Key<T>> keys_;
    std::vector<std::vector<std::size_t>> byProperty_;  ///< per property, the keys giving it
};

/// Reads an array of keyframes of one object.
template <typename T>
Track<T> parseTrack(const JsonNode& array) {
    std::vector<Key<T>> keys;
    for (const JsonNode& k : array.elements()) {
        k.requireObject();
        Key<T> key;
        const JsonNode frame = k.at("frame");
        key.frame = static_cast<std::uint32_t>(frame.integer(0, Animation::kMaxFrame));
        if (!keys.empty() && key.frame <= keys.back().frame) {
            frame.fail("frame " + std::to_string(key.frame) + " is not after the previous " +
                       "keyframe's " + std::to_string(keys.back().frame) +
                       " (keyframes must be in strictly increasing frame order)");
        }
        key.given = applyProperties(k, key.value, {"frame"});
        key.path = k.path();
        keys.push_back(std::move(key));
    }
    return Track<T>(array.file(), array.path(), std::move(keys));
}

/// A value of `T` unless this base makes it unusable; then the base's.
template <typename T>
T usableOr(T value, const T& fallback) {
    return propertyTable<T>().problem(value) ? fallback : value;
}

}  // namespace

struct Animation::Tracks {
    std::optional<Track<Camera>> camera;
    std::vector<std::pair<std::uint32_t, Track<Transform>>> objects;
    std::vector<std::pair<std::uint32_t, Track<PunctualLight>>> punctualLights;
    std::vector<std::pair<std::uint32_t, Track<QuadLight>>> quadLights;
    /// Every material of the name gets the same keys.
    std::vector<std::pair<std::vector<std::uint32_t>, Track<Material>>> materials;
    std::optional<Track<Environment>> environment;
    std::uint32_t lastKeyFrame = 0;
    bool empty = true;
    // The scene's shape, to refuse a base state of another scene.
    std::size_t meshCount = 0, materialCount = 0, punctualLightCount = 0, quadLightCount = 0;

    template <typename T>
    void count(const Track<T>& track) {
        if (track.empty()) return;
        empty = false;
        lastKeyFrame = std::max(lastKeyFrame, track.lastFrame());
    }
};

namespace {

// A material keyed so that diffuse + specular exceeds 1 is rendered scaled down, as the scene
// loader does with its overrides: warn once, at load time.
void warnAboutEnergy(const Track<Material>& track, const std::vector<std::uint32_t>& indices,
                     const SceneState& base, const std::string& file) {
    for (std::uint32_t i : indices) {
        const auto frame = track.firstFrameWhere(
            base.materials[i], [](const Material& m) { return reflectedPeak(m) > 1.0f; });
        if (!frame) continue;
        spdlog::warn(
            "{}: {}: diffuse + specular reflects more than all the light from frame {} "
            "on: scaled down when rendered",
            file, track.path(), *frame);
        return;
    }
}

}  // namespace

Animation::Animation() : tracks_(std::make_shared<Tracks>()) {}

Animation Animation::parse(const std::string& text, const std::string& fileName,
                           const Scene& scene) {
    const nlohmann::json json = parseJsonText(text, fileName);
    const JsonNode root(json, fileName, "");
    root.checkKeys({"camera", "objects", "lights", "materials", "environment"});
    const SceneState base = SceneState::of(scene);
    const SceneNames names(scene);

    auto tracks = std::make_shared<Tracks>();
    tracks->meshCount = base.transforms.size();
    tracks->materialCount = base.materials.size();
    tracks->punctualLightCount = base.punctualLights.size();
    tracks->quadLightCount = base.quadLights.size();

    if (auto camera = root.find("camera")) {
        tracks->camera = parseTrack<Camera>(*camera);
        tracks->camera->checkEveryFrame(base.camera);
        tracks->count(*tracks->camera);
    }
    if (auto objects = root.find("objects")) {
        for (const auto& [name, keys] : objects->members()) {
            const std::uint32_t mesh = names.mesh(name, keys);
            Track<Transform> track = parseTrack<Transform>(keys);
            track.checkEveryFrame(base.transforms[mesh]);
            tracks->count(track);
            tracks->objects.emplace_back(mesh, std::move(track));
        }
    }
    if (auto lights = root.find("lights")) {
        for (const auto& [name, keys] : lights->members()) {
            const SceneNames::LightRef light = names.light(name, keys);
            if (light.quad) {
                Track<QuadLight> track = parseTrack<QuadLight>(keys);
                track.checkEveryFrame(base.quadLights[light.index]);
                tracks->count(track);
                tracks->quadLights.emplace_back(light.index, std::move(track));
            } else {
                Track<PunctualLight> track = parseTrack<PunctualLight>(keys);
                track.checkEveryFrame(base.punctualLights[light.index]);
                tracks->count(track);
                tracks->punctualLights.emplace_back(light.index, std::move(track));
            }
        }
    }
    if (auto materials = root.find("materials")) {
        for (const auto& [name, keys] : materials->members()) {
            std::vector<std::uint32_t> indices = names.materials(name, keys);
            Track<Material> track = parseTrack<Material>(keys);
            warnAboutEnergy(track, indices, base, fileName);
            tracks->count(track);
            tracks->materials.emplace_back(std::move(indices), std::move(track));
        }
    }

    if (auto environment = root.find("environment")) {
        tracks->environment = parseTrack<Environment>(*environment);
        tracks->count(*tracks->environment);
    }

    Animation animation;
    animation.tracks_ = std::move(tracks);
    return animation;
}

Animation Animation::load(const std::filesystem::path& file, const Scene& scene) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw SceneError::inFile(file.string(), "cannot open the animation file");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw SceneError::inFile(file.string(), "cannot read the animation file");
    return parse(text.str(), file.string(), scene);
}

SceneState Animation::stateAt(std::uint32_t frame, const SceneState& base) const {
    const Tracks& t = *tracks_;
    if (t.empty) return base;
    if (base.transforms.size() != t.meshCount || base.materials.size() != t.materialCount ||
        base.punctualLights.size() != t.punctualLightCount ||
        base.quadLights.size() != t.quadLightCount) {
        throw std::invalid_argument("Animation::stateAt: a base state of another scene");
    }
    SceneState s = base;
    if (t.camera) s.camera = usableOr(t.camera->valueAt(frame, base.camera), base.camera);
    for (const auto& [i, track] : t.objects) {
        s.transforms[i] = usableOr(track.valueAt(frame, base.transforms[i]), base.transforms[i]);
    }
    for (const auto& [i, track] : t.punctualLights)
        s.punctualLights[i] = track.valueAt(frame, base.punctualLights[i]);
    for (const auto& [i, track] : t.quadLights) {
        s.quadLights[i] = usableOr(track.valueAt(frame, base.quadLights[i]), base.quadLights[i]);
    }
    for (const auto& [indices, track] : t.materials) {
        for (std::uint32_t i : indices) {
            s.materials[i] = track.valueAt(frame, base.materials[i]);
            scaleToConserveEnergy(s.materials[i]);
        }
    }
    if (t.environment) s.environment = t.environment->valueAt(frame, base.environment);
    return s;
}

bool Animation::empty() const {
    return tracks_->empty;
}

std::uint32_t Animation::lastKeyFrame() const {
    return tracks_->lastKeyFrame;
}

}  // namespace igi

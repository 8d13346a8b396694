#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "ClientRoster.h"
#include "ControlServer.h"
#include "FrameCompositor.h"
#include "FrameOutputs.h"
#include "MasterOptions.h"
#include "SceneTimeline.h"
#include "Statistics.h"
#include "scene/Scene.h"

namespace igi {

/// Control commands and status (docs/ANIMATION.md, docs/VIEW.md): it parses a command line of
/// igi-ctl or the web view, applies it (a scene change to the timeline, the exposure, a snapshot
/// to the outputs, stop to the session) and answers in JSON; and it describes the session for
/// `status`, `scene` and `pick` and for the view's overlay.
class SessionControl {
  public:
    /// What the commands ask of the session that runs the frames.
    class Frames {
      public:
        virtual ~Frames() = default;
        virtual std::uint32_t framesDone() const = 0;
        /// The first frame a change made now reaches.
        virtual std::uint32_t nextFrame() const = 0;
        /// Ends the session after the frames done (the command has been answered).
        virtual void stop() = 0;
        /// A settings command's new target error (0: none).
        virtual void setTargetError(double target) = 0;
        /// A command changed the scene or its settings (`changed`), or the target: a live
        /// session idle at its target renders again, unless the image shown meets the target
        /// and nothing changed, or its time limit is up.
        virtual void resume(bool changed) = 0;
        /// The error estimate and the limits: merged into the status (Master::errorJson).
        virtual nlohmann::json errorJson() const = 0;
    };

    /// `created`: when the session began (the statistics' clock).
    SessionControl(Frames& frames, const MasterOptions& options, Scene& scene,
                   SceneTimeline& timeline, Statistics& stats, const ClientRoster& roster,
                   const FrameCompositor& compositor, FrameOutputs& outputs,
                   std::chrono::steady_clock::time_point created);

    /// Opens the control port (--control) and the web view's (--view), whose commands come here.
    /// Throws std::runtime_error naming the flag and the address when a port cannot be opened.
    void openPorts(boost::asio::io_context& io);
    /// Closes the control port (the view's is FrameOutputs').
    void closePorts();

    /// Runs one command line from `from` ("igi-ctl" or "view") and answers it (now, or for a
    /// snapshot when it is written). igi-ctl's changes are logged, the view's (a drag sends
    /// dozens a second) only at debug level.
    void handle(const std::string& line, ControlServer::Reply reply, const char* from);
    /// The session's state for `status` commands and the view's overlay.
    nlohmann::json statusJson();
    /// The scene's objects, lights and camera as control commands would set them.
    nlohmann::json sceneJson() const;
    nlohmann::json pickJson(float x, float y) const;

  private:
    Frames& frames_;
    const MasterOptions& options_;
    Scene& scene_;
    SceneTimeline& timeline_;
    Statistics& stats_;
    const ClientRoster& roster_;
    const FrameCompositor& compositor_;
    FrameOutputs& outputs_;
    std::chrono::steady_clock::time_point created_;
    std::unique_ptr<ControlServer> control_;
};

}  // namespace igi

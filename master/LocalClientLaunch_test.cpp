#include "LocalClientLaunch.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace igi {
namespace {

bool has(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

std::string after(const std::vector<std::string>& v, const std::string& flag) {
    const auto it = std::find(v.begin(), v.end(), flag);
    return it == v.end() || it + 1 == v.end() ? std::string() : *(it + 1);
}

TEST(LocalClientLaunch, SharesTheMachineAndConnectsOnLoopbackWhenListeningEverywhere) {
    MasterOptions o;
    o.localClients = 3;
    o.listenHost = "0.0.0.0";
    const LocalClientLaunch l = localClientLaunch(o, 7878, "", 8);
    EXPECT_EQ(after(l.arguments, "--connect"), "127.0.0.1:7878");
    EXPECT_EQ(after(l.arguments, "--threads"), "2");
    EXPECT_EQ(after(l.arguments, "--reconnect-seconds"), "0");
    EXPECT_TRUE(has(l.arguments, "--no-scene-warnings"));
    o.clientThreads = 5;
    o.localClients = 40;
    EXPECT_EQ(after(localClientLaunch(o, 7878, "", 8).arguments, "--threads"), "5");
    o.clientThreads = 0;
    EXPECT_EQ(after(localClientLaunch(o, 7878, "", 8).arguments, "--threads"), "1");
}

// The master's own random secret never appears on a command line (ps shows those to every
// user); a secret file is named, not read into the arguments.
TEST(LocalClientLaunch, TheLocalSecretGoesIntoTheEnvironmentOnly) {
    MasterOptions o;
    o.localClients = 1;
    const LocalClientLaunch l = localClientLaunch(o, 1, "s3cret", 2);
    ASSERT_EQ(l.environment.size(), 1u);
    EXPECT_EQ(l.environment[0], "IGI_SECRET=s3cret");
    for (const std::string& a : l.arguments) EXPECT_EQ(a.find("s3cret"), std::string::npos) << a;

    o.secretFile = "/etc/igi/secret";
    const LocalClientLaunch f = localClientLaunch(o, 1, "", 2);
    EXPECT_TRUE(f.environment.empty());
    EXPECT_EQ(after(f.arguments, "--secret-file"), "/etc/igi/secret");

    o.insecure = true;
    const LocalClientLaunch i = localClientLaunch(o, 1, "s3cret", 2);
    EXPECT_TRUE(has(i.arguments, "--insecure"));
    EXPECT_TRUE(i.environment.empty());
}

}  // namespace
}  // namespace igi

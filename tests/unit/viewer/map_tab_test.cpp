// MapTab: export and import send a MapFileRequest for the typed path; an empty or too long path
// shows an error and sends nothing.
#include "viewer/core/map_tab.hpp"

#include <gtest/gtest.h>

#include "fake_command_sink.hpp"

namespace slam::viewer {
namespace {

class MapTabTest : public ::testing::Test {
 protected:
  ViewerState state{100};
  FakeCommandSink sink;
  MapTab tab;
};

TEST_F(MapTabTest, ExportSendsThePath) {
  tab.path = "/data/office.yaml";
  tab.export_map(state, sink);
  ASSERT_EQ(sink.map_files.size(), 1u);
  EXPECT_FALSE(sink.map_files[0].import);
  EXPECT_EQ(sink.map_files[0].yaml_path, "/data/office.yaml");
  EXPECT_TRUE(tab.error.empty());
  EXPECT_NE(state.status_line.find("export /data/office.yaml"), std::string::npos);
}

TEST_F(MapTabTest, ImportSendsThePath) {
  tab.path = "/data/office.yaml";
  tab.import_map(state, sink);
  ASSERT_EQ(sink.map_files.size(), 1u);
  EXPECT_TRUE(sink.map_files[0].import);
  EXPECT_EQ(sink.map_files[0].yaml_path, "/data/office.yaml");
}

TEST_F(MapTabTest, EmptyPathIsRefused) {
  tab.path.clear();
  tab.export_map(state, sink);
  tab.import_map(state, sink);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MapTabTest, TooLongPathIsRefused) {
  tab.path.assign(kMaxMapPath + 1, 'p');
  tab.import_map(state, sink);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MapTabTest, RefusedSendShowsAnError) {
  sink.refuse = true;
  tab.export_map(state, sink);
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos);
}

TEST_F(MapTabTest, MapperRepliesAreKeptNewestFirst) {
  IntakeBatch batch;
  batch.replies.push_back({1, 0, "exported"});
  batch.replies.push_back({2, 3, "cannot write"});
  state.ingest(batch, 0);
  ASSERT_EQ(state.replies.size(), 2u);
  EXPECT_EQ(state.replies.front().request_id, 2u);
  EXPECT_NE(state.status_line.find("failed"), std::string::npos);
}

}  // namespace
}  // namespace slam::viewer

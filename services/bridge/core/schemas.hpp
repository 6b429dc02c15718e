#pragma once
// The JSON schemas the bridge advertises, compiled in from services/bridge/schemas/*.json (the
// foxglove.* ones are Foxglove's own message schemas without their prose; the slam.* ones are the
// bridge's). Generated at configure time from schemas.cpp.in.
namespace slam::bridge::schemas {

extern const char* const kGrid;             // foxglove.Grid
extern const char* const kSceneUpdate;      // foxglove.SceneUpdate
extern const char* const kFrameTransforms;  // foxglove.FrameTransforms
extern const char* const kPointCloud;       // foxglove.PointCloud
extern const char* const kServiceHealth;    // slam.ServiceHealth
extern const char* const kAlerts;           // slam.Alerts
extern const char* const kPathRequest;      // slam.PathRequest
extern const char* const kPathResponse;     // slam.PathResponse

}  // namespace slam::bridge::schemas

// room: an architectural room in the spirit of the paper's Room scene, made of axis-aligned boxes. One
// quadrant (x > 0, y > 0) is furnished and mirrored into the other three, so the room's symmetries are
// the two vertical mirror planes and the half-turn between them (C2v).
#include "sample_scenes.hpp"

#include <cstdint>

namespace symcompress::samples {
namespace {

struct Box {
    int material;
    Eigen::Vector3d centre;
    Eigen::Vector3d size;
};

enum RoomMaterial { kFloor, kWall, kWood, kRedBooks, kBlueBooks };

// A chair whose back is on the side `away` (+1 or -1 along y) from the table it faces.
void addChair(std::vector<Box>& boxes, const Eigen::Vector3d& at, double away) {
    boxes.push_back({kWood, at + Eigen::Vector3d(0, 0, 0.475), {0.45, 0.45, 0.05}});
    for (double x : {-0.19, 0.19})
        for (double y : {-0.19, 0.19}) boxes.push_back({kWood, at + Eigen::Vector3d(x, y, 0.225), {0.04, 0.04, 0.45}});
    // Narrower than the seat and set in from its edge, so that no edge of the back lies on one of the seat's.
    boxes.push_back({kWood, at + Eigen::Vector3d(0, away * 0.2, 0.75), {0.4, 0.04, 0.5}});
}

void addTable(std::vector<Box>& boxes, const Eigen::Vector3d& at) {
    boxes.push_back({kWood, at + Eigen::Vector3d(0, 0, 0.75), {1.6, 0.9, 0.06}});
    for (double x : {-0.7, 0.7})
        for (double y : {-0.35, 0.35}) boxes.push_back({kWood, at + Eigen::Vector3d(x, y, 0.36), {0.06, 0.06, 0.72}});
    for (double x : {-0.4, 0.4})
        for (double y : {-0.75, 0.75}) addChair(boxes, at + Eigen::Vector3d(x, y, 0), y > 0 ? 1 : -1);
}

// Two sides, six boards, and 36 books on each of the five lower boards, of three sizes in a fixed
// pseudo-random order, a few millimetres apart (books that touched would share edges and become one tile).
void addBookshelf(std::vector<Box>& boxes, const Eigen::Vector3d& at) {
    for (double x : {-0.62, 0.62}) boxes.push_back({kWood, at + Eigen::Vector3d(x, 0, 1.0), {0.04, 0.32, 2.0}});
    const Eigen::Vector3d bookSizes[3] = {{0.02, 0.18, 0.2}, {0.025, 0.2, 0.24}, {0.028, 0.22, 0.28}};
    std::uint32_t state = 12345;
    for (int level = 0; level < 6; ++level) {
        const double boardZ = 0.05 + 0.38 * level;
        boxes.push_back({kWood, at + Eigen::Vector3d(0, 0, boardZ), {1.2, 0.3, 0.03}});
        if (level == 5) break;
        double x = -0.59;
        for (int book = 0; book < 36; ++book) {
            state = state * 1664525u + 1013904223u;
            const int kind = int(state >> 30) % 3;
            const Eigen::Vector3d& size = bookSizes[kind];
            boxes.push_back({kind == 1 ? kBlueBooks : kRedBooks, at + Eigen::Vector3d(x + size.x() / 2, 0, boardZ + 0.015 + size.z() / 2), size});
            x += size.x() + 0.005;
        }
    }
}

}  // namespace

Scene makeRoomScene() {
    std::vector<Box> quadrant;
    addTable(quadrant, {3, 1.5, 0});
    addBookshelf(quadrant, {3, 3.75, 0});
    OneMeshBuilder room("room");
    room.addMaterial("floor", {0.55, 0.45, 0.35, 1});
    room.addMaterial("wall", {0.9, 0.9, 0.85, 1});
    room.addMaterial("wood", {0.6, 0.4, 0.2, 1});
    room.addMaterial("red-books", {0.7, 0.15, 0.1, 1});
    room.addMaterial("blue-books", {0.1, 0.2, 0.6, 1});
    // The walls stand a little apart from the floor and from each other: flush edges would join them.
    room.add(kFloor, boxMesh({0, 0, -0.1}, {12, 8, 0.2}));
    for (double side : {-1.0, 1.0}) {
        room.add(kWall, boxMesh({0, side * 4.2, 1.5}, {12.2, 0.2, 3.0}));
        room.add(kWall, boxMesh({side * 6.3, 0, 1.5}, {0.2, 8.2, 3.0}));
    }
    for (double sx : {1.0, -1.0})
        for (double sy : {1.0, -1.0})
            for (const Box& box : quadrant)
                room.add(box.material, boxMesh({sx * box.centre.x(), sy * box.centre.y(), box.centre.z()}, box.size));
    return std::move(room).build();
}

}  // namespace symcompress::samples

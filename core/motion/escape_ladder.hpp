#pragma once
// What a behaviour tries when a move of its own is blocked (in contact, the wheels stalled, for
// blocked_s): each block since the body last turned freely climbs one rung. The first answer
// depends on what was blocked (a blocked turn backs up, a blocked straight move turns); after
// that every move is tried in turn, so a body wedged at a rear corner — which can neither back
// up nor turn one way — creeps forward or turns the other way instead of alternating between
// the two blocked moves for good (seen over ARCOS: 500 s against a box, wheels stalled).

#include "core/geometry/types.hpp"

namespace irgs {

// The on-the-spot turn of the turn rungs (and of the wall follower's turn away after a back-up).
inline constexpr double kEscapeTurn_rad = degToRad(30.0);

enum class EscapeMove { kBackUp, kTurn, kForward, kTurnOpposite };

class EscapeLadder {
 public:
  // The move to try now that the current one (a turn or not) is blocked.
  EscapeMove next(bool blocked_move_was_turn) {
    if (rung_ < 0)
      rung_ = blocked_move_was_turn ? 0 : 1;
    else
      rung_ = (rung_ + 1) % kRungs;
    ++climbed_;
    return static_cast<EscapeMove>(rung_);
  }
  // The body moved freely (a turn completed): the next block starts at the bottom again.
  void reset() { rung_ = -1; }
  int climbed() const { return climbed_; }  // rungs taken in all

 private:
  static constexpr int kRungs = 4;
  int rung_ = -1;
  int climbed_ = 0;
};

}  // namespace irgs

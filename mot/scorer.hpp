#pragma once
// Pure computation: a prepared sequence in, the raw counts of every metric out. No I/O.
#include "mot/prepared_sequence.hpp"
#include "mot/sequence_counts.hpp"

namespace rtmot::mot {

/// CLEAR MOT exactly as the MOTChallenge devkit's clearMOTMex + CLEAR_MOT_HUN (IoU >= 0.5).
ClearCounts count_clear(const PreparedSequence& sequence);
/// Identity measures (Ristani et al. 2016), IoU >= 0.5, as the devkit's IDmeasures.
IdentityCounts count_identity(const PreparedSequence& sequence);
/// HOTA (Luiten et al. 2020) as TrackEval computes it.
HotaCounts count_hota(const PreparedSequence& sequence);

SequenceCounts count_all(const PreparedSequence& sequence);

}  // namespace rtmot::mot

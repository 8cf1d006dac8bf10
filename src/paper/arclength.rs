//! `plus`, `more2`, `expanding2`: the thesis's own way of making the
//! segment counts equal (§3.2.3 (a), Fig. 3.7), unit `paper`, OCR lines
//! 2879–3011.

use super::{getdistance, saving, Distarray, OneBased, PaperError, PaperMessage, PaperPair, Sdirection};
use crate::options::Fidelity;
use crate::types::{Coeff, SweepShape, MAXSEGMENTS};

/// `plus(nu; pu, pv: coeff; var tu, tv: sdirection; var k)` (unit
/// `paper`, OCR lines 2879–2908): "add more points to the object whose
/// number of segments is less": segment (`pu`, `pv`) goes to `tu[k]`,
/// `tv[k]` and `nu` more copies after it, their `first`, `last` cutting
/// [0, 1] into `nu + 1` equal parameter ranges; `k` moves past them.
///
/// A negative `nu` is the listing's `' error : plus. nu:'`: logged, and the
/// segment is not written (it drops out). Entries past 60 are not written
/// (the Pascal would write past `sdirection`); `k` still moves, so
/// `more2`'s count check reports it.
pub fn plus(
    nu: i64,
    pu: &Coeff,
    pv: &Coeff,
    tu: &mut Sdirection,
    tv: &mut Sdirection,
    k: &mut usize,
    log: &mut Vec<PaperMessage>,
) {
    if nu < 0 {
        log.push(PaperMessage::PlusError { nu });
        return;
    }
    let n = nu as usize;
    if *k == 0 || k.checked_add(n).is_none_or(|end| end > MAXSEGMENTS) {
        *k = k.saturating_add(n).saturating_add(1);
        return;
    }
    tu[*k] = *pu;
    tv[*k] = *pv;
    let mut time = 1.0 / (n as f64 + 1.0);
    let time2 = time;
    for i in 1..=n {
        tu[*k + i] = *pu;
        tv[*k + i] = *pv;
        tu[*k + i].first = time;
        tu[*k + i - 1].last = time;
        tv[*k + i].first = time;
        tv[*k + i - 1].last = time;
        time += time2;
    }
    *k += n + 1;
}

/// `more2(d1, d2: distarray; n1, n2; var pu, pv: sdirection)` (unit
/// `paper`, §3.2.3 (a), Fig. 3.7, OCR lines 2910–2981): the contour `pu`,
/// `pv` of `n1` segments, whose starts are at the shares `d1` of its
/// length, gets `n2 − n1` more, where the other contour (`n2` segments,
/// shares `d2`) has its starts. Erratum 8.
///
/// 1. Segment i (covering d1\[i−1\] ≤ share < d1\[i\]) counts the other contour's
///    starts `d2[j]` in its range: `temp[i]` = that count − 1 points to add.
/// 2. A segment with none (`temp[i] = -1`) takes one from the nearest
///    segment to its left with points to spare, else to its right; if
///    there is none the listing prints `It is impossible`.
/// 3. `plus` cuts each segment into `temp[i] + 1` pieces; the listing
///    prints `o.k : equal` or `error : more2. n2 <> (k-1)`.
///
/// Erratum 8 (`more2`'s part): a start of the other contour at share 1
/// (its last chords have length 0: the last segments start where the
/// first does) lies in no segment's half-open range, so the listing does
/// not count it; with fewer starts counted than n1, step 2 can find no
/// spare point ("It is impossible"), the segment drops out of `plus` and
/// the counts end different. `Fidelity::Listing` logs each line and goes
/// on; `pu`, `pv` then keep what they held past the pieces written (the
/// caller's earlier contents: zero for entries nothing wrote, as the
/// Pascal's fresh global arrays). `Fidelity::Thesis` closes the last
/// segment's range, [d1[n1−1], 1], so every start is counted, the counts
/// of step 1 add up to n2 − n1 > 0, and step 2 always finds a spare point:
/// the counts always end equal; it would return the failure as `Err`.
#[allow(clippy::too_many_arguments)]
pub fn more2(
    d1: &Distarray,
    d2: &Distarray,
    n1: usize,
    n2: usize,
    pu: &mut Sdirection,
    pv: &mut Sdirection,
    fidelity: Fidelity,
    log: &mut Vec<PaperMessage>,
) -> Result<(), PaperMessage> {
    let (n1, n2) = (n1.min(MAXSEGMENTS), n2.min(MAXSEGMENTS));
    let mut tu = Sdirection::default();
    let mut tv = Sdirection::default();
    let mut temp = OneBased::<i64, 70>::default();
    let mut k = 1;
    let mut j = 0;
    for i in 1..=n1 {
        let mut add = 0;
        let mut ok = true;
        while j < n2 && ok {
            let inside = match fidelity {
                // Erratum 8, listing: (d2[j] < d1[i]) and (d2[j] >= d1[i-1]).
                Fidelity::Listing => d2[j] < d1[i] && d2[j] >= d1[i - 1],
                // Thesis: the last segment's range is closed at share 1.
                Fidelity::Thesis => (i == n1 || d2[j] < d1[i]) && d2[j] >= d1[i - 1],
            };
            if inside {
                add += 1;
                j += 1;
            } else {
                ok = false;
            }
        }
        temp[i] = add - 1;
    }

    for i in 1..=n1 {
        if temp[i] < 0 {
            let mut ok = true;
            let mut j = i - 1;
            while ok && j > 0 {
                if temp[j] > 0 {
                    temp[j] -= 1;
                    ok = false;
                    temp[i] = 0;
                } else {
                    j -= 1;
                }
            }
            if ok {
                j = i + 1;
                while ok && j <= n1 {
                    if temp[j] > 0 {
                        temp[j] -= 1;
                        ok = false;
                        temp[i] = 0;
                    } else {
                        j += 1;
                    }
                }
            }
            if ok {
                let message = PaperMessage::Impossible { segment: i };
                match fidelity {
                    // Erratum 8, listing: writeln('It is impossible ') and go on.
                    Fidelity::Listing => log.push(message),
                    Fidelity::Thesis => return Err(message),
                }
            }
        }
    }

    for i in 1..=n1 {
        plus(temp[i], &pu[i], &pv[i], &mut tu, &mut tv, &mut k, log);
    }
    for i in 1..k.min(MAXSEGMENTS + 1) {
        pu[i] = tu[i];
        pv[i] = tv[i];
    }
    if n2 != k - 1 {
        let message = PaperMessage::More2Unequal { n2, k1: k - 1 };
        match fidelity {
            // Erratum 8, listing: writeln(' error : more2. n2 <> (k-1) ',…).
            Fidelity::Listing => log.push(message),
            Fidelity::Thesis => return Err(message),
        }
    } else {
        log.push(PaperMessage::More2Equal);
    }
    Ok(())
}

/// `expanding2(int; var obj1, obj2)` (unit `paper`, §3.2.3 (a), OCR lines
/// 2983–3011): "let the number of segments of obj1 and obj2 be equal by
/// the algorithm msc's paper": save both contours (`p1u`, `p1v`, `p2u`,
/// `p2v` of pair `int`), `getdistance` of each (`dist3`, `dist4`), then
/// `more2` on the one with fewer segments, whose `segment` becomes the
/// other's (even when `more2` failed, as printed). Erratum 8: in
/// `Fidelity::Thesis` a failure of `more2` is returned as
/// [`PaperError::Method`]; `Fidelity::Listing` goes on.
pub fn expanding2(int: &mut PaperPair, obj1: &mut SweepShape, obj2: &mut SweepShape) -> Result<(), PaperError> {
    saving(obj1, &mut int.p1u, &mut int.p1v);
    saving(obj2, &mut int.p2u, &mut int.p2v);
    let s1 = obj1.segment;
    let s2 = obj2.segment;
    let mut dist3: Distarray = [0.0; MAXSEGMENTS + 1];
    let mut dist4: Distarray = [0.0; MAXSEGMENTS + 1];
    getdistance(&int.p1u, &int.p1v, s1, &mut dist3);
    getdistance(&int.p2u, &int.p2v, s2, &mut dist4);
    let fidelity = int.fidelity;
    let result = if s1 < s2 {
        let r = more2(
            &dist3,
            &dist4,
            s1,
            s2,
            &mut int.p1u,
            &mut int.p1v,
            fidelity,
            &mut int.messages,
        );
        obj1.segment = s2;
        r
    } else {
        let r = more2(
            &dist4,
            &dist3,
            s2,
            s1,
            &mut int.p2u,
            &mut int.p2v,
            fidelity,
            &mut int.messages,
        );
        obj2.segment = s1;
        r
    };
    result.map_err(|message| PaperError::Method { int: int.int, message })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plus_cuts_into_equal_ranges() {
        let p = Coeff {
            a: 1.0,
            last: 1.0,
            ..Coeff::default()
        };
        let (mut tu, mut tv) = (Sdirection::default(), Sdirection::default());
        let mut k = 2;
        let mut log = Vec::new();
        plus(3, &p, &p, &mut tu, &mut tv, &mut k, &mut log);
        assert_eq!(k, 6);
        let cuts: Vec<(f64, f64)> = (2..=5).map(|i| (tu[i].first, tu[i].last)).collect();
        assert_eq!(cuts, [(0.0, 0.25), (0.25, 0.5), (0.5, 0.75), (0.75, 1.0)]);
        assert!(log.is_empty());
        plus(-1, &p, &p, &mut tu, &mut tv, &mut k, &mut log);
        assert_eq!(k, 6);
        assert_eq!(log, [PaperMessage::PlusError { nu: -1 }]);
        // Past 60: nothing written, k moves on.
        let mut k = 59;
        plus(3, &p, &p, &mut tu, &mut tv, &mut k, &mut log);
        assert_eq!(k, 63);
        assert_eq!(tu[60], Coeff::default());
    }

    fn shares(v: &[f64]) -> Distarray {
        let mut d = [0.0; MAXSEGMENTS + 1];
        d[..v.len()].copy_from_slice(v);
        d
    }

    fn numbered(n: usize) -> Sdirection {
        let mut p = Sdirection::default();
        for i in 1..=n {
            p[i] = Coeff {
                d: i as f64,
                last: 1.0,
                ..Coeff::default()
            };
        }
        p
    }

    #[test]
    fn more2_follows_the_starts_of_the_other_contour() {
        // 2 segments at shares 0, ½; the other's 5 starts at 0, .1, .2, .3, .6:
        // segment 1 takes four, segment 2 one.
        let d1 = shares(&[0.0, 0.5, 1.0]);
        let d2 = shares(&[0.0, 0.1, 0.2, 0.3, 0.6, 1.0]);
        for f in [Fidelity::Listing, Fidelity::Thesis] {
            let (mut pu, mut pv) = (numbered(2), numbered(2));
            let mut log = Vec::new();
            assert_eq!(more2(&d1, &d2, 2, 5, &mut pu, &mut pv, f, &mut log), Ok(()));
            let from: Vec<f64> = (1..=5).map(|i| pu[i].d).collect();
            assert_eq!(from, [1.0, 1.0, 1.0, 1.0, 2.0]);
            assert_eq!(log, [PaperMessage::More2Equal]);
        }
    }

    #[test]
    fn more2_borrows_left_then_right() {
        // Segment 2 of 3 ([.4, .5)) gets no start: it borrows from segment 1.
        let d1 = shares(&[0.0, 0.4, 0.5, 1.0]);
        let d2 = shares(&[0.0, 0.1, 0.2, 0.6, 1.0]);
        let (mut pu, mut pv) = (numbered(3), numbered(3));
        let mut log = Vec::new();
        assert_eq!(
            more2(&d1, &d2, 3, 4, &mut pu, &mut pv, Fidelity::Listing, &mut log),
            Ok(())
        );
        let from: Vec<f64> = (1..=4).map(|i| pu[i].d).collect();
        assert_eq!(from, [1.0, 1.0, 2.0, 3.0]);
        // Segment 1 of 3 has length 0 and gets none: it borrows from the
        // right (segment 2 holds 0, .2 and .3; segment 3 holds .6).
        let d1 = shares(&[0.0, 0.0, 0.5, 1.0]);
        let d2 = shares(&[0.0, 0.2, 0.3, 0.6, 1.0]);
        let (mut pu, mut pv) = (numbered(3), numbered(3));
        assert_eq!(
            more2(&d1, &d2, 3, 4, &mut pu, &mut pv, Fidelity::Listing, &mut log),
            Ok(())
        );
        let from: Vec<f64> = (1..=4).map(|i| pu[i].d).collect();
        assert_eq!(from, [1.0, 2.0, 2.0, 3.0]);
    }
}

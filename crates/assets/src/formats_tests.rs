//! Unit tests of the asset readers and writers.
use super::*;

#[test]
fn mask_round_trip_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.r16");
    let m = Mask::new(4, (0..16).rev().collect()).unwrap();
    save_mask(&m, &p).unwrap();
    assert_eq!(load_mask(&p).unwrap(), m);
    std::fs::write(&p, [0u8; 20]).unwrap();
    assert!(
        load_mask(&p)
            .unwrap_err()
            .to_string()
            .contains("not a square")
    );
    std::fs::write(&p, [0u8; 32]).unwrap();
    assert!(load_mask(&p).unwrap_err().to_string().contains("twice"));
    std::fs::write(&p, [0u8; 2 * 36]).unwrap();
    assert!(
        load_mask(&p)
            .unwrap_err()
            .to_string()
            .contains("power of two")
    );
    let e = load_mask(&dir.path().join("missing.r16")).unwrap_err();
    assert!(matches!(e, AssetError::Io { .. }), "{e}");
}

#[test]
fn from_bytes_rejects_bad_sides_without_panicking() {
    let p = Path::new("x.r16");
    // n * n * 2 overflows usize: once a division by zero.
    assert!(StbnVolume::from_bytes(&[0; 8], usize::MAX, p).is_err());
    assert!(StbnVolume::from_bytes(&[0; 8], 1 << 33, p).is_err());
    assert!(StbnVolume::from_bytes(&[0; 8], 0, p).is_err());
    assert!(StbnVolume::from_bytes(&[], 4, p).is_err());
    assert!(Mask::from_bytes(&[], p).is_err());
    assert!(Mask::from_bytes(&[1], p).is_err());
    let m = Mask::new(2, vec![3, 1, 0, 2]).unwrap();
    assert_eq!(Mask::from_bytes(&m.to_bytes(), p).unwrap(), m);
}

#[test]
fn stbn_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("v.r16");
    let mut ranks: Vec<u16> = (0..16).collect();
    ranks.extend((0..16).rev());
    let v = StbnVolume::new(4, 2, ranks).unwrap();
    save_stbn(&v, &p).unwrap();
    let back = load_stbn(&p, 4).unwrap();
    assert_eq!(back, v);
    assert_eq!(back.slice(1).unwrap().ranks[0], 15);
    assert!(load_stbn(&p, 8).is_err());
}

#[test]
fn retarget_round_trip_and_validation() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("t.bin");
    // Swap (0,0) and (1,0); everything else stays.
    let mut off = vec![(0i8, 0i8); 16];
    off[0] = (1, 0);
    off[1] = (-1, 0);
    let t = RetargetTable::new(4, (3, 2), 1, off.clone()).unwrap();
    save_retarget(&t, &p).unwrap();
    assert_eq!(std::fs::metadata(&p).unwrap().len(), 16 + 32);
    assert_eq!(load_retarget(&p).unwrap(), t);
    let mut bad = off.clone();
    bad[1] = (0, 0);
    let e = RetargetTable::new(4, (3, 2), 1, bad).unwrap_err();
    assert!(e.to_string().contains("bijection"), "{e}");
    let mut far = vec![(0i8, 0i8); 16];
    far[0] = (1, 1);
    far[5] = (-1, -1);
    assert!(
        RetargetTable::new(4, (0, 0), 1, far)
            .unwrap_err()
            .to_string()
            .contains("radius")
    );
    let mut bytes = t.to_bytes();
    bytes[0] = b'X';
    assert!(RetargetTable::from_bytes(&bytes, &p).is_err());
    bytes = t.to_bytes();
    bytes.pop();
    assert!(RetargetTable::from_bytes(&bytes, &p).is_err());
    // Fuzz finding (retarget target): a non-zero reserved header field was accepted, so a
    // table that parsed did not write back the same bytes.
    bytes = t.to_bytes();
    bytes[15] = 0x10;
    let e = RetargetTable::from_bytes(&bytes, &p).unwrap_err();
    assert!(e.to_string().contains("reserved"), "{e}");
}

//! Google GnssLogger's `.txt` of a simulated walk, as [`crate::io::import::gnss_logger`] reads
//! it. May import: `engine` and `io`.

use super::{get_orientation, java_float, js, Item, Walk};
use std::fmt::Write as _;

impl Walk<'_> {
    /// Google GnssLogger v3: the `# Kind,…` declarations, then `Accel`, `Gyro`, `Mag` (values as
    /// Java prints floats), `OrientationDeg` (getOrientation's azimuth, roll and pitch in
    /// degrees) and `Fix` lines in time order; `utcTimeMillis` Unix ms, `elapsedRealtimeNanos`
    /// since boot. A fix's unknown speed and bearing are empty.
    pub(super) fn gnss_logger(&self) -> Vec<(String, Vec<u8>)> {
        let mut out = String::from(GNSS_LOGGER_HEADER);
        for item in &self.items {
            match item {
                Item::Imu(s) => {
                    let (ms, ns) = (self.unix_ms(s.t), self.boot_ns(s.t));
                    for (kind, v) in [("Accel", Some(s.accel)), ("Gyro", s.gyro), ("Mag", s.mag)] {
                        if let Some(v) = v {
                            let _ = writeln!(
                                out,
                                "{kind},{ms},{ns},{},{},{}",
                                java_float(v.x),
                                java_float(v.y),
                                java_float(v.z)
                            );
                        }
                    }
                    if let Some(q) = s.orientation {
                        let (a, p, r) = get_orientation(&q);
                        let _ = writeln!(
                            out,
                            "OrientationDeg,{ms},{ns},{},{},{}",
                            java_float(a.to_degrees()),
                            java_float(r.to_degrees()),
                            java_float(p.to_degrees())
                        );
                    }
                }
                Item::Fix(f) => {
                    let opt = |v: Option<f64>| v.map_or(String::new(), java_float);
                    let _ = writeln!(
                        out,
                        "Fix,GPS,{},{},{},{},{},{},{},,,{},{},0,24,,",
                        js(f.lat_deg),
                        js(f.lon_deg),
                        f.altitude_m.map_or(String::new(), js),
                        opt(f.speed_mps),
                        java_float(f.h_accuracy_m),
                        opt(f.bearing_deg),
                        self.unix_ms(f.t),
                        self.boot_ns(f.t),
                        java_float(1.5 * f.h_accuracy_m),
                    );
                }
            }
        }
        vec![(
            format!("gnss_log_{}.txt", self.name('_', '_', '_')),
            out.into_bytes(),
        )]
    }
}

const GNSS_LOGGER_HEADER: &str = "# \n# Header Description:\n# \n\
# Version: v3.0.6.0 Platform: 14 Manufacturer: pdr Model: simulator GnssHardwareModelName: pdr-sim\n# \n\
# Raw,utcTimeMillis,TimeNanos,LeapSecond,TimeUncertaintyNanos,FullBiasNanos,BiasNanos,BiasUncertaintyNanos,DriftNanosPerSecond,DriftUncertaintyNanosPerSecond,HardwareClockDiscontinuityCount,Svid,TimeOffsetNanos,State,ReceivedSvTimeNanos,ReceivedSvTimeUncertaintyNanos,Cn0DbHz,PseudorangeRateMetersPerSecond,PseudorangeRateUncertaintyMetersPerSecond\n# \n\
# UncalAccel,utcTimeMillis,elapsedRealtimeNanos,UncalAccelXMps2,UncalAccelYMps2,UncalAccelZMps2,BiasXMps2,BiasYMps2,BiasZMps2\n# \n\
# UncalGyro,utcTimeMillis,elapsedRealtimeNanos,UncalGyroXRadPerSec,UncalGyroYRadPerSec,UncalGyroZRadPerSec,DriftXRadPerSec,DriftYRadPerSec,DriftZRadPerSec\n# \n\
# UncalMag,utcTimeMillis,elapsedRealtimeNanos,UncalMagXMicroT,UncalMagYMicroT,UncalMagZMicroT,BiasXMicroT,BiasYMicroT,BiasZMicroT\n# \n\
# Fix,Provider,LatitudeDegrees,LongitudeDegrees,AltitudeMeters,SpeedMps,AccuracyMeters,BearingDegrees,UnixTimeMillis,SpeedAccuracyMps,BearingAccuracyDegrees,elapsedRealtimeNanos,VerticalAccuracyMeters,MockLocation,NumberOfUsedSignals,VerticalSpeedAccuracyMps,SolutionType\n# \n\
# Status,UnixTimeMillis,SignalCount,SignalIndex,ConstellationType,Svid,CarrierFrequencyHz,Cn0DbHz,AzimuthDegrees,ElevationDegrees,UsedInFix,HasAlmanacData,HasEphemerisData,BasebandCn0DbHz\n# \n\
# OrientationDeg,utcTimeMillis,elapsedRealtimeNanos,yawDeg,rollDeg,pitchDeg\n# \n\
# Accel,utcTimeMillis,elapsedRealtimeNanos,AccelXMps2,AccelYMps2,AccelZMps2\n# \n\
# Gyro,utcTimeMillis,elapsedRealtimeNanos,GyroXRadPerSec,GyroYRadPerSec,GyroZRadPerSec\n# \n\
# Mag,utcTimeMillis,elapsedRealtimeNanos,MagXMicroT,MagYMicroT,MagZMicroT\n# \n";

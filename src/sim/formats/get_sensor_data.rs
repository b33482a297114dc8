//! GetSensorData's `.txt` of a simulated walk, with `POSI` landmarks, as
//! [`crate::io::import::get_sensor_data`] reads it. May import: `engine` and `io`.

use super::{canonical, civil, fixed, get_orientation, ms_text, waypoints, Item, Walk, BOOT_NS};
use crate::sim::{GnssSim, Simulation};
use std::fmt::Write as _;

impl Walk<'_> {
    /// GetSensorData (IPIN): the `%` header, then `ACCE`, `GYRO`, `MAGN` (5 decimals), `AHRS`
    /// (getOrientation's pitch, roll and azimuth in degrees, then the rotation vector x, y, z with
    /// w ≥ 0 implied, 8 decimals), `GNSS` (each fix twice, 1 ms apart, as the app does; Android
    /// reports an unknown speed or bearing as 0), `PRES` (mbar = hPa, 4 decimals, with the same
    /// delivery delays as the inertial sensors) and `POSI` landmarks with their floor
    /// ([`landmark_floor`]), in `AppTimestamp` order.
    /// `AppTimestamp` is seconds since the start of the recording plus a delivery delay of
    /// 0–10 ms that varies from sample to sample and is 0 for every eleventh; `SensorTimestamp`
    /// is seconds since boot. The reader's least-delay offset therefore puts each sample back at
    /// its time since the start.
    pub(super) fn get_sensor_data(&self, sim: &Simulation) -> Vec<(String, Vec<u8>)> {
        let mut lines = self.gsd_record_lines();
        lines.extend(self.gsd_pressure_lines());
        lines.extend(self.gsd_landmark_lines(sim));
        // Stable: lines of the same `AppTimestamp` keep the order above.
        crate::engine::sort::sort_by_key(&mut lines, |l| l.0);
        let mut out = self.gsd_header();
        for (_, l) in lines {
            out.push_str(&l);
            out.push('\n');
        }
        vec![(
            format!("logfile_{}.txt", self.name('_', '_', '_')),
            out.into_bytes(),
        )]
    }

    /// The `ACCE`, `GYRO`, `MAGN` and `AHRS` lines of the IMU samples and the `GNSS` lines of
    /// the fixes, each with its `AppTimestamp` in ms, in record order.
    fn gsd_record_lines(&self) -> Vec<(i64, String)> {
        let mut lines: Vec<(i64, String)> = Vec::new();
        let boot_ms = BOOT_NS.div_euclid(1_000_000);
        let mut k = 0i64;
        for item in &self.items {
            match item {
                Item::Imu(s) => {
                    let rel = self.rel_ms(s.t);
                    let app = rel + (k * 7) % 11;
                    k += 1;
                    let (a, st) = (ms_text(app), ms_text(boot_ms.saturating_add(rel)));
                    for (kind, v) in [("ACCE", Some(s.accel)), ("GYRO", s.gyro), ("MAGN", s.mag)] {
                        if let Some(v) = v {
                            lines.push((
                                app,
                                format!(
                                    "{kind};{a};{st};{};{};{};3",
                                    fixed(v.x, 5),
                                    fixed(v.y, 5),
                                    fixed(v.z, 5)
                                ),
                            ));
                        }
                    }
                    if let Some(q) = s.orientation {
                        let (az, p, r) = get_orientation(&q);
                        let c = canonical(&q);
                        lines.push((
                            app,
                            format!(
                                "AHRS;{a};{st};{};{};{};{};{};{};3",
                                fixed(p.to_degrees(), 2),
                                fixed(r.to_degrees(), 2),
                                fixed(az.to_degrees(), 2),
                                fixed(c.i, 8),
                                fixed(c.j, 8),
                                fixed(c.k, 8)
                            ),
                        ));
                    }
                }
                Item::Fix(f) => {
                    let app = self.rel_ms(f.t);
                    let line = |app: i64| {
                        format!(
                            "GNSS;{};{};{};{};{};{};{};{};12;9",
                            ms_text(app),
                            ms_text(self.unix_ms(f.t)),
                            fixed(f.lat_deg, 8),
                            fixed(f.lon_deg, 8),
                            fixed(f.altitude_m.unwrap_or(0.0), 1),
                            fixed(f.bearing_deg.unwrap_or(0.0), 1),
                            fixed(f.h_accuracy_m, 1),
                            fixed(f.speed_mps.unwrap_or(0.0), 1)
                        )
                    };
                    lines.push((app, line(app)));
                    lines.push((app + 1, line(app + 1)));
                }
            }
        }
        lines
    }

    /// The `PRES` lines of the barometer, each with its `AppTimestamp` in ms.
    fn gsd_pressure_lines(&self) -> Vec<(i64, String)> {
        let boot_ms = BOOT_NS.div_euclid(1_000_000);
        let mut lines = Vec::new();
        for (k, p) in self.pressure.iter().enumerate() {
            let rel = self.rel_ms(p.t);
            let app = rel + (k as i64 * 7) % 11;
            lines.push((
                app,
                format!(
                    "PRES;{};{};{};3",
                    ms_text(app),
                    ms_text(boot_ms.saturating_add(rel)),
                    fixed(p.hpa, 4)
                ),
            ));
        }
        lines
    }

    /// The `POSI` landmarks at the walk's [`waypoints`], each with its `AppTimestamp` in ms.
    fn gsd_landmark_lines(&self, sim: &Simulation) -> Vec<(i64, String)> {
        let frame = geodetic_frame(sim);
        let mut lines = Vec::new();
        for (i, (t, e, n)) in waypoints(sim).into_iter().enumerate() {
            let (lat, lon, _) = frame.to_geodetic([e, n, 0.0]);
            let app = self.rel_ms(t);
            lines.push((
                app,
                format!(
                    "POSI;{};{};{};{};{};0",
                    ms_text(app),
                    i + 1,
                    fixed(lat, 7),
                    fixed(lon, 7),
                    landmark_floor(sim, t)
                ),
            ));
        }
        lines
    }

    /// The `%` header: the app, the date of creation (the start, UTC), the phone and the line
    /// formats.
    fn gsd_header(&self) -> String {
        let (y, mo, d, h, mi, s, wd) = civil(self.unix_start_ns.div_euclid(1_000_000_000));
        const DAYS: [&str; 7] = ["Sun", "Mon", "Tue", "Wed", "Thu", "Fri", "Sat"];
        const MONTHS: [&str; 12] = [
            "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
        ];
        let mut out = String::from(
            "% LogFile created by the 'GetSensorData' App for Android.\n% Date of creation: ",
        );
        let _ = writeln!(
            out,
            "{} {} {d:02} {h:02}:{mi:02}:{s:02} UTC {y}",
            DAYS[wd as usize % 7],
            MONTHS[(mo as usize + 11) % 12]
        );
        out.push_str(GET_SENSOR_DATA_HEADER);
        out
    }
}

/// The floor ID written in a `POSI` landmark at simulation time `t`: the true floor there.
fn landmark_floor(sim: &Simulation, t: f64) -> i32 {
    sim.truth.floor_at(t)
}

/// The geodetic frame of the true path: the simulation's, or one at [`GnssSim`]'s default
/// origin for a walk without GNSS.
fn geodetic_frame(sim: &Simulation) -> crate::engine::geo::LocalFrame {
    sim.truth.frame.unwrap_or_else(|| {
        let o = GnssSim::default().origin;
        crate::engine::geo::LocalFrame::new(o.0, o.1, o.2)
    })
}

const GET_SENSOR_DATA_HEADER: &str = "% Developed by LOPSI research group at CAR-CSIC, Spain (http://www.car.upm-csic.es/lopsi)\n\
% Version 2.1 January 2018\n\
% The 'GetSensorData' program stores information from Smartphone/Tablet internal sensors (Accelerometers, Gyroscopes, Magnetometers, Pressure, Ambient Light, Orientation, Sound level, GPS/GNSS position, WiFi RSS, Cellular/GSM/3G signal strength,...)\n\
%\n\
% Phone used for this logfile:\n\
% Manufacturer:            \tpdr\n\
% Model:                   \tsimulator\n\
% API Android version:     \t29\n\
%\n\
% LogFile Data format:\n\
% Accelerometer data: \t'ACCE;AppTimestamp(s);SensorTimestamp(s);Acc_X(m/s^2);Acc_Y(m/s^2);Acc_Z(m/s^2);Accuracy(integer)'\n\
% Gyroscope data:     \t'GYRO;AppTimestamp(s);SensorTimestamp(s);Gyr_X(rad/s);Gyr_Y(rad/s);Gyr_Z(rad/s);Accuracy(integer)'\n\
% Magnetometer data:  \t'MAGN;AppTimestamp(s);SensorTimestamp(s);Mag_X(uT);;Mag_Y(uT);Mag_Z(uT);Accuracy(integer)'\n\
% Pressure data:      \t'PRES;AppTimestamp(s);SensorTimestamp(s);Pres(mbar);Accuracy(integer)'\n\
% Light data:         \t'LIGH;AppTimestamp(s);SensorTimestamp(s);Light(lux);Accuracy(integer)'\n\
% Orientation data:   \t'AHRS;AppTimestamp(s);SensorTimestamp(s);PitchX(deg);RollY(deg);YawZ(deg);Quat(2);Quat(3);Quat(4);Accuracy(int)'\n\
% GNSS data:          \t'GNSS;AppTimestamp(s);SensorTimeStamp(s);Latit(deg);Long(deg);Altitude(m);Bearing(deg);Accuracy(m);Speed(m/s);SatInView;SatInUse'\n\
% WIFI data:          \t'WIFI;AppTimestamp(s);SensorTimeStamp(s);Name_SSID;MAC_BSSID;Frequency;RSS(dBm);'\n\
% BLE 4.0 data:       \t'BLE4;AppTimestamp(s);iBeacon;MAC;RSSI(dBm);MajorID;MinorID;'\n\
% Sound data:         \t'SOUN;AppTimestamp(s);RMS;Pressure(Pa);SPL(dB);'\n\
% Ground truth data:  \t'POSI;Timestamp(s);Counter;Latitude(degrees); Longitude(degrees);floor ID(0,1,2..4);Building ID(0,1,2..3)'\n\
%\n\
% Note that there are two timestamps:\n\
%  -'AppTimestamp' is set by the Android App as data is read. It is not representative of when data is actually captured by the sensor (but has a common time reference for all sensors)\n\
%  -'SensorTimestamp' is set by the sensor itself (the delta_time=SensorTimestamp(k)-SensorTimestamp(k-1) between two consecutive samples is an accurate estimate of the sampling interval). This timestamp is better for integrating inertial data.\n";

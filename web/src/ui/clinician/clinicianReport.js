// What the clinician view reports in window.glasshead: pure functions of its state, so that the
// end-to-end tests and the view read the same figures.
import { frameContacts } from './clinicianFrames.js';

/**
 * window.glasshead.clinician: what is loaded and shown.
 * @param {object} state the view's state
 * @param {{ frames: number, targetFrame: number, squares: number | null, imported?: object }} shown
 *   `imported`: the outcome of the last import ({ ok, message, ids }) or null
 */
export function clinicianReport( state, { frames, targetFrame, squares, imported = null } ) {

	const { target, recording, comparison, frame, playing, loaded, error, speed, target3d } = state;
	return {
		loaded, error, frame, frames, playing, speed,
		target: target ? { name: target.name, label: target.label, frames: target.count, frame: targetFrame } : null,
		recording: recording ? { id: recording.id, name: recording.name, title: recording.title, frames: recording.count, frameRateHz: recording.frameRateHz } : null,
		agreement: comparison ? comparison.agreement[ frame ] : null,
		target3d: target3d ? { rows: target3d.rows, contacted: target3d.contacted, squares } : null,
		meanAgreement: comparison ? comparison.summary.mean_agreement : null,
		kappa: comparison?.kappa ? comparison.kappa[ frame ] : null,
		meanKappa: comparison?.kappa ? comparison.summary.mean_kappa : null,
		// Per phone, when the target says the recording's phones (POST .../coarticulated).
		phones: comparison?.phones ?? null,
		imported,
	};

}

/** window.glasshead.epg in the clinician view: the contacts of the frame shown, real and synthetic. */
export function clinicianEpgReport( state, targetFrame ) {

	const real = frameContacts( state.recording?.frames, state.frame );
	const synthetic = frameContacts( state.target?.frames, targetFrame );
	const shown = real ?? synthetic;
	return { source: 'clinician', frame: state.frame, rows: shown?.rows ?? null, contacted: shown?.contacted ?? 0, percent: shown?.percent ?? 0, recording: real, synthetic };

}

/** An index value for the table: a dash when absent, one decimal from 10 up, else three. */
export function formatIndexValue( value ) {

	if ( value === undefined || value === null ) return '–';
	return Math.abs( value ) >= 10 ? value.toFixed( 1 ) : value.toFixed( 3 );

}

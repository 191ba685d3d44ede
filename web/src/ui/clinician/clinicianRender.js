// The clinician view drawn from its state, pure of fetching: the frame slider and label, the three
// palatograms with their captions (cut with an ellipsis, whole on hover), the table of indices by
// readable name with the direction of the difference, the index curves and the strip of frames.
// `ui` holds the elements clinicianLayout made.

import { EPG_CELLS } from '../../core/constants.js';
import { h } from '../shared/dom.js';
import { indexRows, plotTracks } from './clinicianFrames.js';
import { setCaption } from './clinicianLayout.js';
import { formatIndexValue } from './clinicianReport.js';
import { agreementText, DIFFERENCE_HEADING, indexLabel, phoneScoresText } from './clinicianText.js';

/** The indices of the table, in its order. */
export const TABLE_INDICES = Object.freeze( [ 'percent', 'cog', 'anteriority', 'centrality', 'dorsopalatal', 'alveolar_percent', 'palatal_percent', 'velar_percent' ] );
const TRACK_COLORS = Object.freeze( { recording: '#1f2328', target: '#b4384a' } );

/**
 * Draw `state` (the view's) into `ui`: `count` frames of the time base at `times` (null for one
 * static frame), the target's frame `targetFrame` shown.
 */
export function renderClinician( ui, state, { count, times, targetFrame } ) {

	const { target, recording, comparison, frame } = state;
	for ( const select of [ ui.targetSelect, ui.recordingSelect ] ) select.title = select.selectedOptions[ 0 ]?.textContent ?? '';
	ui.slider.max = String( count - 1 );
	ui.slider.value = String( frame );
	const ms = times ? Math.round( ( times[ frame ] - times[ 0 ] ) * 1000 ) : 0;
	ui.frameLabel.textContent = `Frame ${ frame + 1 } of ${ count }${ times ? ` · ${ ms } ms` : '' }`;

	setCaption( ui.targetCaption, target ? target.label : 'none chosen' );
	ui.targetPalatogram.set( target ? target.frames : null, { offset: Math.max( 0, targetFrame ) * EPG_CELLS } );
	setCaption( ui.recordingCaption, recording ? recording.title : 'none chosen' );
	ui.recordingPalatogram.set( recording ? recording.frames : null, { offset: frame * EPG_CELLS } );
	const phones = phoneScoresText( comparison );
	ui.phoneScores.hidden = phones === null;
	ui.phoneScores.textContent = phones ?? '';
	if ( comparison ) {

		setCaption( ui.agreementCaption, agreementText( comparison, frame ) );
		ui.agreementPalatogram.set( null, { codes: comparison.codeFrames, offset: frame * EPG_CELLS } );

	} else {

		setCaption( ui.agreementCaption, 'choose both' );
		ui.agreementPalatogram.set( null );

	}

	renderTable( ui, state, targetFrame );
	if ( recording || target ) {

		ui.plot.set( plotTracks( state, times, TRACK_COLORS ) );
		ui.stripCaption.textContent = comparison ? 'Agreement over time (click a frame)' : recording ? 'Recording over time (click a frame)' : 'Target over time';
		if ( recording ) ui.strip.set( recording.frames, recording.count, frame, recording.t_s, comparison ? comparison.codeFrames : null );
		else ui.strip.set( target.frames, target.count, frame, target.t_s );

	} else {

		ui.plot.set( { t_s: [], tracks: [] } );
		ui.strip.set( null, 0, 0 );

	}

}

/** The table of indices at the current frame (the target's at `targetFrame`). */
function renderTable( ui, state, targetFrame ) {

	const head = h( 'tr', {}, h( 'th', {}, 'index' ), h( 'th', {}, 'target' ), h( 'th', {}, 'recording' ), h( 'th', {}, `difference (${ DIFFERENCE_HEADING })` ) );
	const rows = indexRows( state, targetFrame, TABLE_INDICES ).map( ( row ) => h( 'tr', {}, h( 'th', { scope: 'row' }, indexLabel( row.name ) ), ...[ row.target, row.recording, row.difference ].map( ( v ) => h( 'td', {}, formatIndexValue( v ) ) ) ) );
	ui.table.replaceChildren( head, ...rows );

}
